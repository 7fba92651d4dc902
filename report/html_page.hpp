#pragma once
// A report directory's index.html as text (docs/plots.md "The report page"): one self-contained
// page — inline CSS, no scripts, no external resources — with a title, a verdict line, the
// printed summary, the figures (relative links to the PNGs beside it), tables, plots not drawn
// and links to the text and data files, in that order. Every text that comes from input
// (scenario and run names, file names, the summary, table cells) is HTML-escaped here; callers
// pass plain text, never markup.

#include <string>
#include <string_view>
#include <vector>

namespace shudder::report {

struct HtmlTable {
  std::string caption;                         // heading above the table
  std::vector<std::string> header;             // column names
  std::vector<std::vector<std::string>> rows;  // each row as many cells as the header
};

struct HtmlFigure {
  std::string file;     // image file name relative to the page, e.g. "torque.png"
  std::string caption;  // what the figure shows; empty = the file name only
};

struct HtmlLink {
  std::string href;         // path relative to the page (not yet URL-encoded)
  std::string text;         // link text
  std::string description;  // what the file holds; may be empty
};

struct HtmlPage {
  std::string title;          // <title> and <h1>
  std::string verdict;        // one sentence under the title; empty = none
  std::string verdict_class;  // "shudder", "none" or "" (neutral): the verdict's colour
  std::string summary;        // preformatted text (the printed summary); empty = none
  std::vector<HtmlTable> tables;
  std::vector<HtmlFigure> figures;
  std::vector<std::string> not_drawn;  // "spectrum.png: why" for plots the data did not support
  std::vector<HtmlLink> files;
};

/// `text` with & < > " ' replaced by character references and control characters other than
/// tab and line breaks dropped, safe in element content and quoted attribute values.
std::string html_escape(std::string_view text);

/// `path` percent-encoded for an href/src attribute: every byte outside A-Z a-z 0-9 - . _ ~ /
/// becomes %XX, so a file name with spaces, '#', '?' or '%' still names the file.
std::string url_path(std::string_view path);

/// The complete document.
std::string html_page_text(const HtmlPage& page);

}  // namespace shudder::report
