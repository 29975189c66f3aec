#include "planet/toml_reader.h"

#include <vector>

namespace planet::toml_reader {
namespace {

// Text that toml++ would reject with a confusing message (or that is not text at all) is
// reported first: empty input, bytes over the size limit, control bytes, invalid UTF-8.
void checkText(const Context& context, std::string_view text, std::string_view expected) {
  if (text.size() > kMaxPresetBytes)
    context.fail(0, fmt::format("too large ({} bytes, limit {})", text.size(), kMaxPresetBytes));
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos)
    context.fail(0, fmt::format("empty document (expected {})", expected));
  uint32_t line = 1, column = 1;
  for (size_t i = 0; i < text.size();) {
    auto byte = uint8_t(text[i]);
    size_t length = byte < 0x80 ? 1 : (byte >> 5) == 0x6 ? 2 : (byte >> 4) == 0xe ? 3 : (byte >> 3) == 0x1e ? 4 : 0;
    bool valid = length != 0 && i + length <= text.size();
    uint32_t codePoint = length == 1 ? byte : byte & (0x7fu >> length);
    for (size_t k = 1; valid && k < length; ++k) {
      auto next = uint8_t(text[i + k]);
      valid = (next & 0xc0) == 0x80;
      codePoint = (codePoint << 6) | (next & 0x3fu);
    }
    // Overlong forms, UTF-16 surrogates and values past U+10FFFF are not UTF-8 either.
    constexpr uint32_t kMinForLength[] = {0, 0, 0x80, 0x800, 0x10000};
    valid = valid && codePoint >= kMinForLength[length] && codePoint <= 0x10ffff &&
            !(codePoint >= 0xd800 && codePoint <= 0xdfff);
    if (!valid)
      throw Error(
          fmt::format("{}:{}:{}: not UTF-8 text (invalid byte 0x{:02x})", context.source(), line, column, byte));
    if ((byte < 0x20 && byte != '\t' && byte != '\n' && byte != '\r') || byte == 0x7f)
      throw Error(fmt::format("{}:{}:{}: not TOML text (control byte 0x{:02x})", context.source(), line, column, byte));
    if (byte == '\n') {
      ++line;
      column = 0;
    }
    ++column;
    i += length;
  }
}

// toml++ builds one table per part of a dotted key or table header ([a.a.a], a.a.a = 1) and
// walks the tree recursively: tens of thousands of parts (a file of 100 kB, well under the
// size limit) overflow the stack. No preset key has more than two parts, so key paths are
// measured before toml++ sees the text. Values nest at most TOML_MAX_NESTED_VALUES deep
// (toml++ checks that), so the depth of the tree stays bounded.
constexpr int kMaxKeyParts = 8;

// Walks the text as TOML: strings and comments are skipped, '[' and '{' in values are tracked,
// and each key path (of a header, a key = value line or an inline table's entry) has its parts
// counted, and non-ASCII bytes outside strings and comments are refused. Malformed text is left
// to toml++ to report, which reads the text in the same order: a deep path is found here before
// toml++ reaches anything that it would reject.
class KeyDepthCheck {
 public:
  KeyDepthCheck(const Context& context, std::string_view text) : context_(context), text_(text) {}

  void run() {
    std::vector<char> open;  // '[' and '{' of the values around the scan position
    bool expectKey = true;   // at a line's start outside values, or after '{' or ',' in an inline table
    while (i_ < text_.size()) {
      const char c = text_[i_];
      // TOML allows non-ASCII text only in strings and comments, which are stepped over here.
      // It is rejected before toml++ sees it: toml++ 3.3 reaches __builtin_unreachable on most
      // such characters where it skips whitespace (upstream issues #190 and #295).
      if (uint8_t(c) >= 0x80)
        context_.fail(line_, "a non-ASCII character outside a string or a comment (TOML keys and values are ASCII)");
      if (c == '\n') {
        ++line_;
        ++i_;
        expectKey = expectKey || open.empty();
      } else if (c == ' ' || c == '\t' || c == '\r') {
        ++i_;
      } else if (c == '#') {
        i_ = std::min(text_.find('\n', i_), text_.size());
      } else if (expectKey) {
        expectKey = false;
        if (open.empty() && c == '[') {  // a header: [table] or [[array]]
          ++i_;
          if (i_ < text_.size() && text_[i_] == '[') ++i_;
        } else if (c == '}' && !open.empty() && open.back() == '{') {  // an empty inline table
          open.pop_back();
          ++i_;
          continue;
        }
        const int parts = keyPath();
        if (parts > kMaxKeyParts)
          context_.fail(line_, fmt::format("a key path of {} parts nests too deep (at most {})", parts, kMaxKeyParts));
        // Not a key at all (toml++ says what it is): step over it, but not over a line's end.
        if (parts == 0 && i_ < text_.size() && text_[i_] != '\n') ++i_;
      } else if (c == '"' || c == '\'') {
        string(true);
      } else {
        ++i_;
        if (c == '[' || c == '{') open.push_back(c);
        if ((c == ']' || c == '}') && !open.empty()) open.pop_back();
        expectKey = (c == '{') || (c == ',' && !open.empty() && open.back() == '{');
      }
    }
  }

 private:
  // Parts of the dotted key at i_ ("a", "b" and "c" of a . "b" . 'c'); stops after the last.
  int keyPath() {
    int parts = 0;
    while (true) {
      skipBlanks();
      if (i_ >= text_.size()) break;
      if (text_[i_] == '"' || text_[i_] == '\'') {
        string(false);
      } else {
        const size_t start = i_;
        while (i_ < text_.size() && isBareKeyByte(text_[i_])) ++i_;
        if (i_ == start) break;
      }
      ++parts;
      skipBlanks();
      if (i_ >= text_.size() || text_[i_] != '.') break;
      ++i_;
    }
    return parts;
  }

  // TOML 1.0 bare keys: ASCII letters, digits, '_' and '-'.
  static bool isBareKeyByte(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  }

  void skipBlanks() {
    while (i_ < text_.size() && (text_[i_] == ' ' || text_[i_] == '\t')) ++i_;
  }

  // Skips the string that starts at i_: basic ("...", with escapes) or literal ('...'), and
  // where `multiLine` allows, their triple-quoted forms (which may hold newlines).
  void string(bool multiLine) {
    const char quote = text_[i_];
    const bool basic = quote == '"';
    const std::string_view triple = basic ? R"(""")" : "'''";
    auto step = [&] { return basic && text_[i_] == '\\' && i_ + 1 < text_.size() && text_[i_ + 1] != '\n' ? 2 : 1; };
    if (multiLine && text_.substr(i_).starts_with(triple)) {
      i_ += 3;
      while (i_ < text_.size() && !text_.substr(i_).starts_with(triple)) {
        if (text_[i_] == '\n') ++line_;
        if (basic && text_[i_] == '\\') backslash();
        i_ += step();
      }
      i_ = std::min(i_ + 3, text_.size());
      // Up to two more quotes belong to the content ("""a"""" ends with a quote).
      for (int k = 0; k < 2 && i_ < text_.size() && text_[i_] == quote; ++k) ++i_;
      return;
    }
    ++i_;
    while (i_ < text_.size() && text_[i_] != quote && text_[i_] != '\n') {
      if (basic && text_[i_] == '\\') backslash();
      i_ += step();
    }
    if (i_ < text_.size() && text_[i_] == quote) ++i_;
  }

  // At a backslash in a basic string. toml++ 3.3 asks whether the characters after it are
  // whitespace (an escape, or a line-ending backslash whose following whitespace and newlines
  // are trimmed) and reaches __builtin_unreachable when the answer is sought for a non-ASCII
  // character (found by the fuzzer). No TOML escape is non-ASCII, so such text is refused here.
  void backslash() const {
    size_t k = i_ + 1;
    while (k < text_.size() && (text_[k] == ' ' || text_[k] == '\t' || text_[k] == '\r')) ++k;
    uint32_t line = line_;
    if (k < text_.size() && text_[k] == '\n')
      while (k < text_.size() && (text_[k] == ' ' || text_[k] == '\t' || text_[k] == '\r' || text_[k] == '\n'))
        line += text_[k++] == '\n';
    if (k < text_.size() && uint8_t(text_[k]) >= 0x80)
      context_.fail(line,
                    "a non-ASCII character after a backslash in a string: not a TOML escape (write it as \\uXXXX, "
                    "or start the line with an ASCII character after a line-ending backslash)");
  }

  const Context& context_;
  std::string_view text_;
  size_t i_ = 0;
  uint32_t line_ = 1;
};

}  // namespace

std::string formatRange(Range range) {
  return fmt::format("[{}, {}]", formatNumber(range.min), formatNumber(range.max));
}

const char* typeName(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table: return "table";
    case toml::node_type::array: return "array";
    case toml::node_type::string: return "string";
    case toml::node_type::integer: return "integer";
    case toml::node_type::floating_point: return "float";
    case toml::node_type::boolean: return "boolean";
    case toml::node_type::date: return "date";
    case toml::node_type::time: return "time";
    case toml::node_type::date_time: return "date-time";
    default: return "nothing";
  }
}

std::string shortened(std::string_view text, size_t limit) {
  size_t end = text.size();
  if (end > limit) {
    end = limit;
    while (end > 0 && (uint8_t(text[end]) & 0xc0) == 0x80) --end;
  }
  std::string out = printable(text.substr(0, end));
  return end < text.size() ? out + "..." : out;
}

std::string oneLine(std::string_view text) { return shortened(text, 200); }

toml::table parseDocument(const Context& context, std::string_view text, std::string_view expected) {
  checkText(context, text, expected);
  KeyDepthCheck(context, text).run();
  try {
    return toml::parse(text, std::string_view(context.source()));
  } catch (const toml::parse_error& e) {
    throw Error(fmt::format("{}:{}:{}: {}", context.source(), e.source().begin.line, e.source().begin.column,
                            oneLine(e.description())));
  }
}

const toml::table& requireTable(const Context& context, const toml::table& root, std::string_view key) {
  const toml::node* node = root.get(key);
  if (!node) context.fail(0, fmt::format("missing table [{}]", key));
  if (!node->is_table()) context.fail(lineOf(*node), fmt::format("'{}' must be a table, got {}", key, typeName(*node)));
  return *node->as_table();
}

const toml::table* optionalTable(const Context& context, const toml::table& root, std::string_view key) {
  const toml::node* node = root.get(key);
  if (!node) return nullptr;
  if (!node->is_table()) context.fail(lineOf(*node), fmt::format("'{}' must be a table, got {}", key, typeName(*node)));
  return node->as_table();
}

}  // namespace planet::toml_reader
