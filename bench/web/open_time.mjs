// How long a page of `raystep export-html` takes to become interactive in Debian's Chromium (headless): from
// the navigation's start to the player's ready mark (its data inflated and parsed, the first step drawn),
// then one step with the key. Best and median of the runs, with the page's size.
//   node bench/web/open_time.mjs PAGE.html [RUNS]
import path from 'node:path';
import fs from 'node:fs';
import { createRequire } from 'node:module';

const [page_file, runs_arg] = process.argv.slice(2);
const here = path.dirname(new URL(import.meta.url).pathname);
const require = createRequire(path.join(here, '..', '..', 'web', 'package.json'));
const { chromium } = require('playwright-core');
const runs = Number(runs_arg || 5);
const browser = await chromium.launch({
  executablePath: process.env.RAYSTEP_CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
         '--disable-component-update', '--disable-sync'],
});
const open = [], step = [];
for (let i = 0; i < runs; ++i) {
  const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
  const t0 = Date.now();
  await page.goto('file://' + path.resolve(page_file));
  await page.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
  open.push(Date.now() - t0);
  const before = await page.evaluate(() => window.raystep.step);
  const t1 = Date.now();
  await page.keyboard.press('ArrowRight');
  await page.waitForFunction((b) => window.raystep.step === b + 1, before);
  step.push(Date.now() - t1);
  await page.close();
}
await browser.close();
const median = (v) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];
console.log(`${page_file}: ${(fs.statSync(page_file).size / 1024).toFixed(1)} KiB; interactive in ` +
            `${Math.min(...open)} ms best, ${median(open)} ms median of ${runs}; a step ${median(step)} ms`);
