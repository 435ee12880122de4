#include "io/npy.h"

#include <gtest/gtest.h>

#include <cstring>

#include "io/camera_test_util.h"

namespace isegman {
namespace {

using testing::expect_error;

// A .npy file with the given version, header dictionary and raw data bytes.
std::vector<uint8_t> npy(int major, const std::string& dict, const std::vector<uint8_t>& data) {
  std::vector<uint8_t> out = {0x93, 'N', 'U', 'M', 'P', 'Y', uint8_t(major), 0};
  std::string h = dict + "\n";
  size_t len = h.size();
  out.push_back(uint8_t(len & 0xff));
  out.push_back(uint8_t(len >> 8));
  if (major >= 2) {
    out.push_back(uint8_t(len >> 16));
    out.push_back(uint8_t(len >> 24));
  }
  out.insert(out.end(), h.begin(), h.end());
  out.insert(out.end(), data.begin(), data.end());
  return out;
}

template <typename T>
std::vector<uint8_t> raw(std::initializer_list<T> values) {
  std::vector<uint8_t> b(values.size() * sizeof(T));
  std::memcpy(b.data(), values.begin(), b.size());
  return b;
}

TEST(Npy, ReadsVersionsOneTwoThreeAndBothFloatTypes) {
  for (int major : {1, 2, 3}) {
    auto f = npy(major, "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }", raw<double>({1, 2, 3, 4, 5, 6.5}));
    NpyArray a = parse_npy(f.data(), f.size(), "a.npy");
    ASSERT_EQ(a.shape, (std::vector<size_t>{2, 3}));
    EXPECT_EQ(a.data, (std::vector<double>{1, 2, 3, 4, 5, 6.5}));
  }
  // float32, double quotes, no trailing comma, 1-D shape, extra spaces.
  auto f = npy(1, "{\"descr\":\"<f4\",\"shape\":(3,),  \"fortran_order\":False}", raw<float>({0.5f, -2.f, 3.25f}));
  NpyArray a = parse_npy(f.data(), f.size(), "b.npy");
  EXPECT_EQ(a.dtype, "<f4");
  ASSERT_EQ(a.shape, (std::vector<size_t>{3}));
  EXPECT_EQ(a.data, (std::vector<double>{0.5, -2, 3.25}));
  // Empty arrays are fine.
  f = npy(1, "{'descr': '<f8', 'fortran_order': False, 'shape': (0, 17), }", {});
  EXPECT_TRUE(parse_npy(f.data(), f.size(), "c.npy").data.empty());
}

TEST(Npy, SerialiseRoundTripsAndAligns) {
  std::vector<double> d = {1.5, -2, 3, 4, 5, 6};
  for (auto shape : {std::vector<size_t>{2, 3}, std::vector<size_t>{6}, std::vector<size_t>{1, 2, 3}}) {
    std::vector<uint8_t> f = serialize_npy(shape, d);
    EXPECT_EQ((f.size() - 8 * d.size()) % 64, 0u);
    NpyArray a = parse_npy(f.data(), f.size(), "x.npy");
    EXPECT_EQ(a.shape, shape);
    EXPECT_EQ(a.data, d);
  }
  std::vector<uint8_t> f = serialize_npy({6}, d);
  std::string header(f.begin() + 10, f.begin() + 64);
  EXPECT_NE(header.find("'shape': (6,)"), std::string::npos) << header;
}

TEST(Npy, RefusesWhatItCannotRead) {
  const std::string ok_tail = "'fortran_order': False, 'shape': (2,), }";
  auto bad_dtype = [&](const std::string& descr, size_t item) {
    return npy(1, "{'descr': '" + descr + "', " + ok_tail, std::vector<uint8_t>(2 * item, 0));
  };
  for (auto [descr, item, msg] : {std::tuple<const char*, size_t, const char*>{"<i8", 8, "unsupported .npy dtype '<i8'"},
                                  {">f8", 8, "big-endian"},
                                  {"<f2", 2, "unsupported"},
                                  {"|u1", 1, "unsupported"}}) {
    auto f = bad_dtype(descr, item);
    expect_error([&] { parse_npy(f.data(), f.size(), "w.npy"); }, {"w.npy", msg});
  }
  auto f = npy(1, "{'descr': '<f8', 'fortran_order': True, 'shape': (2,), }", raw<double>({1, 2}));
  expect_error([&] { parse_npy(f.data(), f.size(), "w.npy"); }, {"Fortran"});
  f = npy(1, "{'descr': [('a', '<f8')], 'fortran_order': False, 'shape': (2,), }", raw<double>({1, 2}));
  expect_error([&] { parse_npy(f.data(), f.size(), "w.npy"); }, {"malformed .npy header"});
  f = npy(1, "{'descr': '<f8', 'shape': (2,), }", raw<double>({1, 2}));
  expect_error([&] { parse_npy(f.data(), f.size(), "w.npy"); }, {"no 'fortran_order'"});
  f = npy(4, "{'descr': '<f8', 'fortran_order': False, 'shape': (2,), }", raw<double>({1, 2}));
  expect_error([&] { parse_npy(f.data(), f.size(), "w.npy"); }, {"version 4"});
  // Truncated and trailing data; a shape whose element count overflows.
  f = npy(1, "{'descr': '<f8', 'fortran_order': False, 'shape': (3,), }", raw<double>({1, 2}));
  expect_error([&] { parse_npy(f.data(), f.size(), "w.npy"); }, {"truncated or trailing"});
  f = npy(1, "{'descr': '<f8', 'fortran_order': False, 'shape': (1,), }", raw<double>({1, 2}));
  expect_error([&] { parse_npy(f.data(), f.size(), "w.npy"); }, {"trailing"});
  f = npy(1, "{'descr': '<f8', 'fortran_order': False, 'shape': (4611686018427387904, 4611686018427387904), }",
          raw<double>({1, 2}));
  expect_error([&] { parse_npy(f.data(), f.size(), "w.npy"); }, {"truncated"});
  f = npy(1, "{'descr': '<f8', 'fortran_order': False, 'shape': (99999999999999999999999,), }", {});
  expect_error([&] { parse_npy(f.data(), f.size(), "w.npy"); }, {"too large"});
  // Header length beyond the file, every truncation of a good file, and no magic.
  f = npy(1, "{'descr': '<f8', 'fortran_order': False, 'shape': (2,), }", raw<double>({1, 2}));
  for (size_t n = 0; n < f.size(); ++n) expect_error([&] { parse_npy(f.data(), n, "t.npy"); }, {"t.npy"});
  std::vector<uint8_t> text = {'[', '1', ']'};
  expect_error([&] { parse_npy(text.data(), text.size(), "t.npy"); }, {"magic"});
}

}  // namespace
}  // namespace isegman
