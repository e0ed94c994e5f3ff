// The browser player's files (web/player), compiled into the library by web/embed_assets.cmake.
#pragma once

namespace raystep::web::assets {

extern const char player_html[];
extern const char player_css[];
extern const char player_js[];
extern const char view3d_js[];  // player/view3d.js bundled with three.js by esbuild

}  // namespace raystep::web::assets
