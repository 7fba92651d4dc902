// index.html text of a report directory; see html_page.hpp.
#include "report/html_page.hpp"

#include <cstdio>
#include <sstream>

namespace shudder::report {

namespace {

// Readable on screen and in print; figures scale down to the window's width.
constexpr const char* kStyle = R"css(
body { font-family: sans-serif; max-width: 72rem; margin: 1.5rem auto; padding: 0 1rem; color: #222; }
h1 { font-size: 1.6rem; margin-bottom: 0.3rem; }
h2 { font-size: 1.25rem; margin-top: 2rem; border-bottom: 1px solid #ccc; }
.verdict { font-size: 1.15rem; padding: 0.5rem 0.8rem; border-left: 0.4rem solid #7f7f7f; background: #f4f4f4; }
.verdict.shudder { border-color: #d62728; background: #fdeeee; }
.verdict.none { border-color: #2ca02c; background: #eef8ee; }
pre { background: #f8f8f8; padding: 0.8rem; overflow-x: auto; font-size: 0.9rem; }
table { border-collapse: collapse; margin: 0.5rem 0; }
th, td { border: 1px solid #ccc; padding: 0.2rem 0.6rem; text-align: left; vertical-align: top; }
th { background: #eee; }
figure { margin: 1rem 0 2rem 0; }
figure img { max-width: 100%; height: auto; border: 1px solid #ddd; }
figcaption { font-size: 0.95rem; color: #444; margin-top: 0.3rem; }
)css";

void table(std::ostringstream& o, const HtmlTable& t) {
  if (!t.caption.empty()) o << "<h2>" << html_escape(t.caption) << "</h2>\n";
  o << "<table>\n";
  if (!t.header.empty()) {
    o << "<thead><tr>";
    for (const auto& h : t.header) o << "<th>" << html_escape(h) << "</th>";
    o << "</tr></thead>\n";
  }
  o << "<tbody>\n";
  for (const auto& row : t.rows) {
    o << "<tr>";
    for (const auto& c : row) o << "<td>" << html_escape(c) << "</td>";
    o << "</tr>\n";
  }
  o << "</tbody>\n</table>\n";
}

}  // namespace

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default:
        // Control characters (other than tab and line breaks) have no place in a page.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') break;
        if (c == 0x7f) break;
        out += c;
    }
  }
  return out;
}

std::string url_path(std::string_view path) {
  std::string out;
  for (char c : path) {
    const auto u = static_cast<unsigned char>(c);
    const bool plain = (u >= 'A' && u <= 'Z') || (u >= 'a' && u <= 'z') || (u >= '0' && u <= '9') || c == '-' ||
                       c == '.' || c == '_' || c == '~' || c == '/';
    if (plain) {
      out += c;
    } else {
      char buf[4];
      std::snprintf(buf, sizeof buf, "%%%02X", u);
      out += buf;
    }
  }
  return out;
}

std::string html_page_text(const HtmlPage& page) {
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
    << "<title>" << html_escape(page.title) << "</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n"
    << "<h1>" << html_escape(page.title) << "</h1>\n";
  if (!page.verdict.empty()) {
    o << "<p class=\"verdict";
    if (!page.verdict_class.empty()) o << " " << html_escape(page.verdict_class);
    o << "\" id=\"verdict\">" << html_escape(page.verdict) << "</p>\n";
  }
  if (!page.summary.empty()) o << "<h2>Summary</h2>\n<pre id=\"summary\">" << html_escape(page.summary) << "</pre>\n";
  if (!page.figures.empty()) {
    o << "<h2>Figures</h2>\n";
    for (const auto& f : page.figures) {
      const std::string src = html_escape(url_path(f.file));
      o << "<figure>\n<a href=\"" << src << "\"><img src=\"" << src << "\" alt=\""
        << html_escape(f.caption.empty() ? f.file : f.caption) << "\"></a>\n<figcaption><b>" << html_escape(f.file)
        << "</b>" << (f.caption.empty() ? "" : ": ") << html_escape(f.caption) << "</figcaption>\n</figure>\n";
    }
  }
  for (const auto& t : page.tables) table(o, t);
  if (!page.not_drawn.empty()) {
    o << "<h2>Not drawn</h2>\n<ul>\n";
    for (const auto& s : page.not_drawn) o << "<li>" << html_escape(s) << "</li>\n";
    o << "</ul>\n";
  }
  if (!page.files.empty()) {
    o << "<h2>Files</h2>\n<ul>\n";
    for (const auto& l : page.files) {
      o << "<li><a href=\"" << html_escape(url_path(l.href)) << "\">" << html_escape(l.text) << "</a>";
      if (!l.description.empty()) o << ": " << html_escape(l.description);
      o << "</li>\n";
    }
    o << "</ul>\n";
  }
  o << "</body>\n</html>\n";
  return o.str();
}

}  // namespace shudder::report
