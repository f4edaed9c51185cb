// cloudlut_manifest.h — the optional part of the engine reader: manifest.json and the JSON
// descriptions of the binary tables (lut_formats/FORMAT.md sections 2.2 and 4).
//
// C++17, standard library only: a minimal JSON parser (just enough for these documents) and
// the manifest's table list. Includes cloudlut_lut.h, the binary table reader.
//
//   cloudlut_reader::Manifest m = cloudlut_reader::readManifest("luts");
//   for (const auto& t : m.tables) { ... t.name, t.binFile, t.exrFile, t.dims ... }
//   cloudlut_reader::Json d = cloudlut_reader::parseDescription(lut);  // a table's parameters
//
// Every error is a std::runtime_error whose message starts with the file name.
#ifndef CLOUDLUT_MANIFEST_H
#define CLOUDLUT_MANIFEST_H

#include <cctype>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "cloudlut_lut.h"

namespace cloudlut_reader {

// A JSON value: just enough JSON for manifest.json and the header description.
struct Json {
  enum class Type { Null, Bool, Number, String, Array, Object };
  Type type = Type::Null;
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<Json> items;        // array elements, or object values
  std::vector<std::string> keys;  // object keys, parallel to items

  // The member named `key` of an object, or nullptr.
  const Json* find(const std::string& key) const {
    if (type != Type::Object) return nullptr;
    for (std::size_t k = 0; k < keys.size(); ++k)
      if (keys[k] == key) return &items[k];
    return nullptr;
  }
};

// Parses a complete JSON text; throws std::runtime_error naming `name` and the offset.
Json parseJson(const std::string& text, const std::string& name = "json");

// The table's header description parsed (an empty description gives an empty object).
Json parseDescription(const Lut& lut);

struct ManifestTable {
  std::string name;
  std::array<std::uint32_t, 4> dims{};
  std::string sampleType;  // "u8", "half" or "float" as described, may be empty
  std::vector<std::string> channels;
  std::string binFile;  // relative to the LUT directory, empty if absent
  std::string exrFile;
};

struct Manifest {
  int version = 0;
  std::string generator;
  std::vector<ManifestTable> tables;  // in document order
  Json document;
};

// Reads dir/manifest.json.
Manifest readManifest(const std::string& dir);

// ---------------------------------------------------------------------------------------------
// Implementation.

namespace detail {

// A recursive-descent JSON parser with a nesting limit.
class JsonParser {
 public:
  JsonParser(const std::string& text, const std::string& name) : s_(text), name_(name) {}

  Json document() {
    Json v = value(0);
    skipSpace();
    if (pos_ != s_.size()) error("trailing characters");
    return v;
  }

 private:
  [[noreturn]] void error(const std::string& what) const {
    fail(name_, "invalid JSON at offset " + std::to_string(pos_) + " (" + what + ")");
  }
  void skipSpace() {
    while (pos_ < s_.size() &&
           (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\n' || s_[pos_] == '\r'))
      ++pos_;
  }
  bool consume(const char* word) {
    const std::size_t n = std::strlen(word);
    if (s_.compare(pos_, n, word) != 0) return false;
    pos_ += n;
    return true;
  }
  Json value(int depth) {
    if (depth > 64) error("nested too deeply");
    skipSpace();
    if (pos_ >= s_.size()) error("unexpected end");
    Json v;
    const char c = s_[pos_];
    if (c == '{') {
      v.type = Json::Type::Object;
      ++pos_;
      skipSpace();
      if (pos_ < s_.size() && s_[pos_] == '}') {
        ++pos_;
        return v;
      }
      for (;;) {
        skipSpace();
        if (pos_ >= s_.size() || s_[pos_] != '"') error("expected a key");
        v.keys.push_back(string());
        skipSpace();
        if (pos_ >= s_.size() || s_[pos_] != ':') error("expected ':'");
        ++pos_;
        v.items.push_back(value(depth + 1));
        skipSpace();
        if (pos_ < s_.size() && s_[pos_] == ',') { ++pos_; continue; }
        if (pos_ < s_.size() && s_[pos_] == '}') { ++pos_; return v; }
        error("expected ',' or '}'");
      }
    }
    if (c == '[') {
      v.type = Json::Type::Array;
      ++pos_;
      skipSpace();
      if (pos_ < s_.size() && s_[pos_] == ']') {
        ++pos_;
        return v;
      }
      for (;;) {
        v.items.push_back(value(depth + 1));
        skipSpace();
        if (pos_ < s_.size() && s_[pos_] == ',') { ++pos_; continue; }
        if (pos_ < s_.size() && s_[pos_] == ']') { ++pos_; return v; }
        error("expected ',' or ']'");
      }
    }
    if (c == '"') {
      v.type = Json::Type::String;
      v.string = string();
      return v;
    }
    if (consume("true")) { v.type = Json::Type::Bool; v.boolean = true; return v; }
    if (consume("false")) { v.type = Json::Type::Bool; return v; }
    if (consume("null")) return v;
    v.type = Json::Type::Number;
    v.number = number();
    return v;
  }
  // A number per the JSON grammar, converted with strtod.
  double number() {
    const std::size_t start = pos_;
    if (pos_ < s_.size() && s_[pos_] == '-') ++pos_;
    const std::size_t digits = pos_;
    while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    if (pos_ == digits) error("expected a value");
    if (pos_ < s_.size() && s_[pos_] == '.') {
      ++pos_;
      while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    }
    if (pos_ < s_.size() && (s_[pos_] == 'e' || s_[pos_] == 'E')) {
      ++pos_;
      if (pos_ < s_.size() && (s_[pos_] == '+' || s_[pos_] == '-')) ++pos_;
      while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    }
    const std::string token = s_.substr(start, pos_ - start);
    return std::strtod(token.c_str(), nullptr);
  }
  // Four hex digits of a \u escape.
  std::uint32_t hex4() {
    if (pos_ + 4 > s_.size()) error("short \\u escape");
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = s_[pos_++];
      v <<= 4;
      if (c >= '0' && c <= '9') v |= static_cast<std::uint32_t>(c - '0');
      else if (c >= 'a' && c <= 'f') v |= static_cast<std::uint32_t>(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F') v |= static_cast<std::uint32_t>(c - 'A' + 10);
      else error("bad \\u escape");
    }
    return v;
  }
  static void appendUtf8(std::string& out, std::uint32_t cp) {
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xc0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xe0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    } else {
      out += static_cast<char>(0xf0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3f));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    }
  }
  // A string starting at the opening quote, escapes resolved, UTF-8 kept as is.
  std::string string() {
    ++pos_;
    std::string out;
    for (;;) {
      if (pos_ >= s_.size()) error("unterminated string");
      const char c = s_[pos_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) error("control character in a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (pos_ >= s_.size()) error("unterminated string");
      const char e = s_[pos_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          std::uint32_t cp = hex4();
          if (cp >= 0xd800 && cp < 0xdc00 && s_.compare(pos_, 2, "\\u") == 0) {
            pos_ += 2;
            const std::uint32_t low = hex4();
            if (low < 0xdc00 || low > 0xdfff) error("bad surrogate pair");
            cp = 0x10000 + ((cp - 0xd800) << 10) + (low - 0xdc00);
          }
          appendUtf8(out, cp);
          break;
        }
        default: error("bad escape");
      }
    }
  }

  const std::string& s_;
  const std::string& name_;
  std::size_t pos_ = 0;
};

}  // namespace detail

inline Json parseJson(const std::string& text, const std::string& name) {
  return detail::JsonParser(text, name).document();
}

// The JSON description in a table's header (FORMAT.md section 2.2): its parameters, axes and
// channels as the baker wrote them; an empty description reads as an empty object.
inline Json parseDescription(const Lut& lut) {
  if (lut.description.empty()) {
    Json empty;
    empty.type = Json::Type::Object;
    return empty;
  }
  return parseJson(lut.description, lut.name);
}

// Reads dir/manifest.json, checks its format and version, and lists its tables.
inline Manifest readManifest(const std::string& dir) {
  const std::string path = (dir.empty() ? std::string(".") : dir) + "/manifest.json";
  std::ifstream in(path, std::ios::binary);
  if (!in) detail::fail(path, "missing or unreadable");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Manifest m;
  m.document = parseJson(text, path);
  const Json* format = m.document.find("format");
  if (format == nullptr || format->type != Json::Type::String || format->string != "cloudlut-lut-set")
    detail::fail(path, "not a cloudlut manifest (\"format\" is not \"cloudlut-lut-set\")");
  const Json* version = m.document.find("version");
  if (version == nullptr || version->type != Json::Type::Number)
    detail::fail(path, "manifest has no \"version\"");
  if (version->number != 1.0 && version->number != 2.0 && version->number != 3.0)
    detail::fail(path, "unsupported manifest version " + std::to_string(version->number) +
                           " (this reader reads 1 to 3)");
  m.version = static_cast<int>(version->number);
  if (const Json* g = m.document.find("generator"); g && g->type == Json::Type::String)
    m.generator = g->string;
  const Json* tables = m.document.find("tables");
  if (tables == nullptr || tables->type != Json::Type::Object)
    detail::fail(path, "manifest has no \"tables\" object");
  for (std::size_t k = 0; k < tables->keys.size(); ++k) {
    const Json& entry = tables->items[k];
    ManifestTable t;
    t.name = tables->keys[k];
    const Json* dims = entry.find("dims");
    if (dims == nullptr || dims->type != Json::Type::Array || dims->items.size() != 4)
      detail::fail(path, "table '" + t.name + "' has no \"dims\"");
    for (std::size_t d = 0; d < 4; ++d) {
      const double n = dims->items[d].number;
      if (dims->items[d].type != Json::Type::Number || !(n >= 1.0) || n > 4294967295.0)
        detail::fail(path, "table '" + t.name + "' has bad \"dims\"");
      t.dims[d] = static_cast<std::uint32_t>(n);
    }
    if (const Json* s = entry.find("sample_type"); s && s->type == Json::Type::String)
      t.sampleType = s->string;
    if (const Json* channels = entry.find("channels"); channels && channels->type == Json::Type::Array)
      for (const Json& c : channels->items)
        if (const Json* n = c.find("name"); n && n->type == Json::Type::String)
          t.channels.push_back(n->string);
    const Json* files = entry.find("files");
    if (files == nullptr || files->type != Json::Type::Object)
      detail::fail(path, "table '" + t.name + "' has no \"files\" object");
    if (const Json* b = files->find("bin"); b && b->type == Json::Type::String) t.binFile = b->string;
    if (const Json* e = files->find("exr"); e && e->type == Json::Type::String) t.exrFile = e->string;
    if (t.binFile.empty() && t.exrFile.empty())
      detail::fail(path, "table '" + t.name + "' lists no file");
    m.tables.push_back(std::move(t));
  }
  return m;
}

}  // namespace cloudlut_reader

#endif  // CLOUDLUT_MANIFEST_H
