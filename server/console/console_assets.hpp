#pragma once
// The console's page (server/console/web/), compiled into netmc-server at build time: what a
// browser gets for /, /console.js and /console.css, wherever the server is installed.

#include <string_view>

namespace netmc::console {

// "index.html", "console.js" or "console.css"; an empty view for any other name.
std::string_view console_asset(std::string_view name);

}  // namespace netmc::console
