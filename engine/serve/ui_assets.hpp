#pragma once
// The live view's page: the files of ui/ (index.html, app.js, style.css), compiled into
// the binary by CMake (engine/serve/ui_assets.cpp.in), so the page needs no network and
// no install.
#include <string>
#include <string_view>

namespace hapscene {

// One file of ui/ by name ("app.js"); empty when there is none.
std::string_view ui_asset(std::string_view name);

// index.html with app.js and style.css inlined (one request loads the page, and the
// token in its address is all it needs).
std::string live_page_html();

}  // namespace hapscene
