// Bundles the player's 3D view with three.js into one script (web/CMakeLists.txt runs it at build time):
//   node web/bundle.mjs IN.js OUT.js
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const esbuild = require('esbuild');
const [entry, outfile] = process.argv.slice(2);
esbuild.buildSync({ entryPoints: [entry], outfile, bundle: true, minify: true, format: 'iife',
                    globalName: 'raystepView3d', legalComments: 'none', logLevel: 'warning' });
