#pragma once
// Loads a report's index.html in a real headless browser (Debian's `chromium`) and reports what
// a reader would see go wrong: images that did not load (naturalWidth 0) and script or resource
// errors. The page is copied beside itself with a check script injected first in <head> (so
// relative links resolve as in the original); the script collects `error` events from the start
// and, on `load`, appends <pre id="browser-check"> with the findings, which --dump-dom prints.
// A missing marker means the check itself did not run: that is a failure, never a pass.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "tests/support/cli.hpp"

namespace shudder::test {

struct BrowserCheck {
  bool ran = false;                 // the marker was found in the dumped DOM
  int images = 0;                   // <img> elements on the page
  std::vector<std::string> broken;  // src of every image that did not load
  std::vector<std::string> errors;  // script errors and resources that failed
  std::string dom;                  // the dumped DOM (for failure messages)
  std::string log;                  // chromium's stderr
};

/// The chromium executable, or "" when none is installed (tests skip then).
inline std::string chromium_executable() {
  for (const char* name : {"chromium", "chromium-browser"}) {
    const std::string probe = std::string("command -v ") + name + " >/dev/null 2>&1";
    if (std::system(probe.c_str()) == 0) return name;
  }
  return "";
}

inline constexpr const char* kChromiumMissing =
    "chromium not installed (Debian: apt-get install chromium; scripts/install-deps.sh installs it): "
    "the report page is not checked in a browser";

namespace browser_detail {

inline constexpr const char* kCheckScript = R"js(<script>
window.__check_errors = [];
window.addEventListener('error', function (e) {
  var t = e.target;
  if (t && t !== window && (t.src || t.href)) window.__check_errors.push('resource ' + (t.src || t.href));
  else window.__check_errors.push('script ' + e.message);
}, true);
window.addEventListener('load', function () {
  var imgs = document.images, broken = [];
  for (var i = 0; i < imgs.length; ++i)
    if (!imgs[i].complete || imgs[i].naturalWidth === 0) broken.push(imgs[i].getAttribute('src'));
  var out = document.createElement('pre');
  out.id = 'browser-check';
  out.textContent = 'images=' + imgs.length + '\nbroken=' + broken.join('\t') + '\nerrors=' +
                    window.__check_errors.join('\t') + '\nend';
  document.body.appendChild(out);
});
</script>
)js";

inline std::vector<std::string> split_tabs(const std::string& s) {
  std::vector<std::string> out;
  std::size_t from = 0;
  while (from < s.size()) {
    const std::size_t tab = s.find('\t', from);
    out.push_back(s.substr(from, tab == std::string::npos ? std::string::npos : tab - from));
    if (tab == std::string::npos) break;
    from = tab + 1;
  }
  return out;
}

}  // namespace browser_detail

/// Opens `page` in headless chromium (`exe`) and returns what the check script found.
inline BrowserCheck check_in_browser(const std::filesystem::path& page, const std::string& exe) {
  namespace fs = std::filesystem;
  BrowserCheck c;
  std::string html = slurp(page);
  const std::size_t head = html.find("<head>");
  if (head == std::string::npos) {
    c.errors.push_back("the page has no <head>");
    return c;
  }
  html.insert(head + 6, browser_detail::kCheckScript);
  const fs::path copy = page.parent_path() / ("browser_check_" + std::to_string(::getpid()) + ".html");
  write_file(copy, html);
  const fs::path profile = fs::temp_directory_path() / ("shudder_chromium_profile_" + std::to_string(::getpid()));
  const fs::path dom = page.parent_path() / "browser_check_dom.txt", log = page.parent_path() / "browser_check_log.txt";
  const std::string cmd = "timeout 120 " + exe +
                          " --headless --disable-gpu --no-sandbox --no-first-run --user-data-dir='" + profile.string() +
                          "' --virtual-time-budget=10000 --dump-dom 'file://" + fs::absolute(copy).string() + "' >'" +
                          dom.string() + "' 2>'" + log.string() + "'";
  (void)std::system(cmd.c_str());
  c.dom = slurp(dom);
  c.log = slurp(log);
  fs::remove(copy);
  fs::remove(dom);
  fs::remove(log);
  std::error_code ec;
  fs::remove_all(profile, ec);
  std::smatch m;
  const std::regex marker("<pre id=\"browser-check\">images=([0-9]+)\nbroken=([^\n]*)\nerrors=([^\n]*)\nend</pre>");
  if (!std::regex_search(c.dom, m, marker)) return c;
  c.ran = true;
  c.images = std::stoi(m[1].str());
  c.broken = browser_detail::split_tabs(m[2].str());
  c.errors = browser_detail::split_tabs(m[3].str());
  return c;
}

/// Every relative href/src on `page` that names no file beside it (percent-decoded, relative to
/// the page's directory): links a reader would find dead.
inline std::vector<std::string> dead_links(const std::filesystem::path& page) {
  namespace fs = std::filesystem;
  const std::string html = slurp(page);
  const std::regex attr("(href|src)=\"([^\"#]+)\"");
  std::vector<std::string> dead;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), attr); it != std::sregex_iterator(); ++it) {
    const std::string raw = (*it)[2].str();
    if (raw.find("://") != std::string::npos) continue;
    std::string path;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] == '%' && i + 2 < raw.size()) {
        path += static_cast<char>(std::stoi(raw.substr(i + 1, 2), nullptr, 16));
        i += 2;
      } else if (raw.compare(i, 5, "&amp;") == 0) {
        path += '&';
        i += 4;
      } else {
        path += raw[i];
      }
    }
    if (!fs::exists(page.parent_path() / path)) dead.push_back(raw);
  }
  return dead;
}

}  // namespace shudder::test
