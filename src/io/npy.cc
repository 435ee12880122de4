#include "io/npy.h"

#include <cstring>
#include <map>

#include "core/error.h"
#include "io/atomic_file.h"

namespace isegman {

namespace {

const char kMagic[] = "\x93NUMPY";
constexpr size_t kMagicLen = 6;
constexpr size_t kMaxHeader = 1 << 20;  // numpy itself refuses headers above ~10 KB

// A value of the header dictionary: a string, a boolean, or a tuple of integers.
struct Value {
  enum Kind { kString, kBool, kTuple } kind = kString;
  std::string str;
  bool b = false;
  std::vector<size_t> tuple;
};

// Parser for the one Python literal numpy writes: {'descr': '<f8', 'fortran_order':
// False, 'shape': (20, 17), }. Strict: anything else is an error.
class HeaderParser {
 public:
  HeaderParser(const std::string& text, const std::string& src) : s_(text), src_(src) {}

  std::map<std::string, Value> parse() {
    std::map<std::string, Value> dict;
    expect('{');
    while (true) {
      skip_ws();
      if (peek() == '}') {
        ++i_;
        break;
      }
      std::string key = string_literal();
      expect(':');
      Value v = value();
      if (!dict.emplace(key, v).second) fail("key '" + key + "' appears twice");
      skip_ws();
      if (peek() == ',') {
        ++i_;
        continue;
      }
      expect('}');
      break;
    }
    skip_ws();
    if (i_ != s_.size()) fail("unexpected text after the dictionary");
    return dict;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(src_, "malformed .npy header (" + what + " at character " + std::to_string(i_) + ")");
  }
  char peek() const { return i_ < s_.size() ? s_[i_] : '\0'; }
  void skip_ws() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
  }
  void expect(char c) {
    skip_ws();
    if (peek() != c) fail(std::string("expected '") + c + "'");
    ++i_;
  }
  std::string string_literal() {
    skip_ws();
    char q = peek();
    if (q != '\'' && q != '"') fail("expected a quoted string");
    size_t end = s_.find(q, i_ + 1);
    if (end == std::string::npos) fail("unterminated string");
    std::string out = s_.substr(i_ + 1, end - i_ - 1);
    if (out.find('\\') != std::string::npos) fail("escape sequences are not supported");
    i_ = end + 1;
    return out;
  }
  size_t integer() {
    skip_ws();
    size_t start = i_;
    size_t v = 0;
    while (i_ < s_.size() && s_[i_] >= '0' && s_[i_] <= '9') {
      if (v > (SIZE_MAX - 9) / 10) fail("dimension too large");
      v = v * 10 + size_t(s_[i_] - '0');
      ++i_;
    }
    if (i_ == start) fail("expected a non-negative integer");
    if (peek() == 'L') ++i_;  // Python 2 long suffix
    return v;
  }
  Value value() {
    skip_ws();
    Value v;
    char c = peek();
    if (c == '\'' || c == '"') {
      v.kind = Value::kString;
      v.str = string_literal();
    } else if (s_.compare(i_, 4, "True") == 0) {
      v.kind = Value::kBool;
      v.b = true;
      i_ += 4;
    } else if (s_.compare(i_, 5, "False") == 0) {
      v.kind = Value::kBool;
      v.b = false;
      i_ += 5;
    } else if (c == '(') {
      v.kind = Value::kTuple;
      ++i_;
      while (true) {
        skip_ws();
        if (peek() == ')') {
          ++i_;
          break;
        }
        if (v.tuple.size() >= 32) fail("more than 32 dimensions");
        v.tuple.push_back(integer());
        skip_ws();
        if (peek() == ',') {
          ++i_;
          continue;
        }
        expect(')');
        break;
      }
    } else {
      fail("unsupported value (dtype records and other objects are not supported)");
    }
    return v;
  }

  const std::string& s_;
  const std::string& src_;
  size_t i_ = 0;
};

}  // namespace

bool is_npy(const uint8_t* data, size_t size) {
  return size >= kMagicLen && std::memcmp(data, kMagic, kMagicLen) == 0;
}

NpyArray parse_npy(const uint8_t* data, size_t size, const std::string& src) {
  if (!is_npy(data, size)) throw Error(src, "not a .npy file (missing the \\x93NUMPY magic)");
  if (size < kMagicLen + 2 + 2) throw Error(src, "truncated .npy header");
  const int major = data[6], minor = data[7];
  size_t header_len = 0, header_start = 0;
  if (major == 1) {
    header_len = size_t(data[8]) | size_t(data[9]) << 8;
    header_start = 10;
  } else if (major == 2 || major == 3) {
    if (size < 12) throw Error(src, "truncated .npy header");
    header_len = size_t(data[8]) | size_t(data[9]) << 8 | size_t(data[10]) << 16 | size_t(data[11]) << 24;
    header_start = 12;
  } else {
    throw Error(src, "unsupported .npy format version " + std::to_string(major) + "." + std::to_string(minor));
  }
  if (header_len > kMaxHeader) throw Error(src, "implausible .npy header length " + std::to_string(header_len));
  if (header_len > size - header_start)
    throw Error(src, "truncated .npy header: " + std::to_string(header_len) + " bytes announced, " +
                         std::to_string(size - header_start) + " present");
  std::string header(reinterpret_cast<const char*>(data + header_start), header_len);
  // Version 1 and 2 headers are latin-1, version 3 utf-8; the keys we need are ASCII and
  // the dictionary must not hold a NUL.
  if (header.find('\0') != std::string::npos) throw Error(src, "malformed .npy header (NUL byte)");

  std::map<std::string, Value> dict = HeaderParser(header, src).parse();
  auto field = [&](const char* key, Value::Kind kind) -> const Value& {
    auto it = dict.find(key);
    if (it == dict.end()) throw Error(src, std::string(".npy header has no '") + key + "'");
    if (it->second.kind != kind) throw Error(src, std::string(".npy header: '") + key + "' has the wrong type");
    return it->second;
  };
  NpyArray a;
  a.dtype = field("descr", Value::kString).str;
  if (field("fortran_order", Value::kBool).b)
    throw Error(src, "Fortran-ordered .npy arrays are not supported (save with C order)");
  a.shape = field("shape", Value::kTuple).tuple;
  if (dict.size() != 3) throw Error(src, ".npy header has unexpected keys");

  size_t item = 0;
  if (a.dtype == "<f8") item = 8;
  else if (a.dtype == "<f4") item = 4;
  else if (a.dtype == ">f8" || a.dtype == ">f4")
    throw Error(src, "big-endian .npy data (" + a.dtype + ") is not supported; expected '<f8' or '<f4'");
  else
    throw Error(src, "unsupported .npy dtype '" + a.dtype + "': expected float64 '<f8' or float32 '<f4'");

  const size_t data_start = header_start + header_len;
  const size_t available = size - data_start;
  size_t count = 1;
  bool empty = false;
  for (size_t d : a.shape) empty |= d == 0;
  for (size_t d : a.shape) {
    if (empty) {
      count = 0;
      break;
    }
    if (count > available / d)
      throw Error(src, "truncated .npy data: the shape needs more elements than the file holds");
    count *= d;
  }
  if (count > available / item || count * item != available)
    throw Error(src, "the .npy data holds " + std::to_string(available) + " bytes, the shape needs " +
                         (count > available / item ? std::string("more") : std::to_string(count * item)) +
                         " (truncated or trailing bytes)");
  a.data.resize(count);
  const uint8_t* p = data + data_start;
  for (size_t i = 0; i < count; ++i) {
    if (item == 8) {
      std::memcpy(&a.data[i], p + 8 * i, 8);
    } else {
      float f;
      std::memcpy(&f, p + 4 * i, 4);
      a.data[i] = f;
    }
  }
  return a;
}

NpyArray read_npy(const std::string& path) {
  std::vector<uint8_t> bytes = read_file_bytes(path);
  return parse_npy(bytes.data(), bytes.size(), path);
}

std::vector<uint8_t> serialize_npy(const std::vector<size_t>& shape, const std::vector<double>& data) {
  size_t count = 1;
  for (size_t d : shape) count *= d;
  if (count != data.size()) throw Error("serialize_npy: shape and data size disagree");
  std::string dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (";
  for (size_t i = 0; i < shape.size(); ++i) dict += (i ? ", " : "") + std::to_string(shape[i]);
  dict += shape.size() == 1 ? ",), }" : "), }";
  // Pad with spaces and a final newline so that the data starts on a 64-byte boundary.
  size_t total = kMagicLen + 2 + 2 + dict.size() + 1;
  dict.append((64 - total % 64) % 64, ' ');
  dict += '\n';
  std::vector<uint8_t> out(kMagic, kMagic + kMagicLen);
  out.push_back(1);
  out.push_back(0);
  out.push_back(uint8_t(dict.size() & 0xff));
  out.push_back(uint8_t(dict.size() >> 8));
  out.insert(out.end(), dict.begin(), dict.end());
  size_t at = out.size();
  out.resize(at + 8 * data.size());
  if (!data.empty()) std::memcpy(out.data() + at, data.data(), 8 * data.size());
  return out;
}

void write_npy(const std::string& path, const std::vector<size_t>& shape, const std::vector<double>& data) {
  write_file_atomic(path, serialize_npy(shape, data));
}

}  // namespace isegman
