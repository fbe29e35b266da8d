#pragma once
// Text inside XML files phedra writes (SVG pages, 3MF models): the characters
// XML reserves, as entities, in element text and in attribute values alike.

#include <string>

namespace phedra {

inline std::string xml_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace phedra
