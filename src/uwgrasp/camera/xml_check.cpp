#include "uwgrasp/camera/xml_check.hpp"

#include <cctype>
#include <vector>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::camera {

namespace {
struct Scan {
  const std::string& t;
  const std::string& file;
  std::size_t i = 0;

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(file + ": malformed XML (" + what + " at byte " + std::to_string(i) + ")");
  }
  bool name_char(char c) const {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' || c == ':';
  }
  std::string name() {
    const std::size_t s = i;
    if (i >= t.size() || !(std::isalpha(static_cast<unsigned char>(t[i])) || t[i] == '_')) fail("expected a name");
    while (i < t.size() && name_char(t[i])) ++i;
    return t.substr(s, i - s);
  }
  void spaces() {
    while (i < t.size() && std::isspace(static_cast<unsigned char>(t[i]))) ++i;
  }
  // Attributes up to the tag's end: name="value" or name='value'.
  void attributes() {
    for (spaces(); i < t.size() && t[i] != '>' && t[i] != '/' && t[i] != '?'; spaces()) {
      name();
      spaces();
      if (i >= t.size() || t[i] != '=') fail("expected '=' after an attribute");
      ++i;
      spaces();
      if (i >= t.size() || (t[i] != '"' && t[i] != '\'')) fail("expected a quoted attribute value");
      const std::size_t close = t.find(t[i], i + 1);
      if (close == std::string::npos) fail("an attribute value is not closed");
      i = close + 1;
    }
  }
  void skip_past(const char* end, const char* what) {
    const std::size_t e = t.find(end, i);
    if (e == std::string::npos) fail(std::string(what) + " is not closed");
    i = e + std::char_traits<char>::length(end);
  }
};
}  // namespace

void check_xml(const std::string& text, const std::string& file) {
  Scan s{text, file};
  std::vector<std::string> open;
  bool root_seen = false;
  while (true) {
    const std::size_t lt = text.find('<', s.i);
    if (lt == std::string::npos) break;
    if (open.empty() && text.find_first_not_of(" \t\r\n", s.i) < lt) s.fail("text outside the root element");
    s.i = lt + 1;
    if (text.compare(s.i, 3, "!--") == 0) {
      s.skip_past("-->", "a comment");
    } else if (text.compare(s.i, 1, "?") == 0) {
      if (root_seen || !open.empty()) s.fail("a declaration after the root element");
      s.i += 1;
      s.name();
      s.attributes();
      if (text.compare(s.i, 2, "?>") != 0) s.fail("the declaration does not end in '?>'");
      s.i += 2;
    } else if (text.compare(s.i, 1, "/") == 0) {
      s.i += 1;
      const std::string n = s.name();
      s.spaces();
      if (open.empty() || open.back() != n) s.fail("</" + n + "> closes nothing open");
      if (s.i >= text.size() || text[s.i] != '>') s.fail("a closing tag does not end in '>'");
      ++s.i;
      open.pop_back();
    } else {
      if (root_seen && open.empty()) s.fail("a second root element");
      const std::string n = s.name();
      s.attributes();
      if (text.compare(s.i, 2, "/>") == 0) {
        s.i += 2;
      } else if (s.i < text.size() && text[s.i] == '>') {
        ++s.i;
        open.push_back(n);
      } else {
        s.fail("a tag does not end in '>'");
      }
      root_seen = true;
    }
  }
  if (!open.empty()) s.fail("<" + open.back() + "> is not closed");
  if (!root_seen) s.fail("no element");
  if (text.find_first_not_of(" \t\r\n", s.i) != std::string::npos) s.fail("text after the root element");
}

}  // namespace uwgrasp::camera
