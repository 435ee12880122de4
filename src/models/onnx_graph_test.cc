// The ONNX executor on small graphs built here: operator semantics where ONNX and ATen
// differ, dynamic shapes, constant folding, and errors that name the node.
#include "models/onnx_graph.h"

#include <gtest/gtest.h>
#include <onnx/onnx_pb.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "core/error.h"
#include "models/tensor_memory.h"

using namespace isegman;
using namespace isegman::models;

namespace {

class Builder {
 public:
  explicit Builder(int opset = 17) {
    m_.set_ir_version(8);
    m_.add_opset_import()->set_version(opset);
    g_ = m_.mutable_graph();
    g_->set_name("test");
  }
  // dims: -1 for a dynamic axis.
  void input(const std::string& name, const std::vector<int64_t>& dims, int elem = onnx::TensorProto_DataType_FLOAT) {
    auto* v = g_->add_input();
    v->set_name(name);
    auto* t = v->mutable_type()->mutable_tensor_type();
    t->set_elem_type(elem);
    for (int64_t d : dims) {
      auto* dim = t->mutable_shape()->add_dim();
      if (d < 0) dim->set_dim_param("N");
      else dim->set_dim_value(d);
    }
  }
  void output(const std::string& name) { g_->add_output()->set_name(name); }
  onnx::NodeProto* node(const std::string& op, const std::vector<std::string>& in, const std::vector<std::string>& out,
                        const std::string& name = "") {
    auto* n = g_->add_node();
    n->set_op_type(op);
    n->set_name(name.empty() ? op + std::to_string(g_->node_size()) : name);
    for (const auto& s : in) n->add_input(s);
    for (const auto& s : out) n->add_output(s);
    return n;
  }
  void floats(const std::string& name, const std::vector<int64_t>& dims, const std::vector<float>& v) {
    auto* t = g_->add_initializer();
    t->set_name(name);
    t->set_data_type(onnx::TensorProto_DataType_FLOAT);
    for (int64_t d : dims) t->add_dims(d);
    for (float f : v) t->add_float_data(f);
  }
  void ints(const std::string& name, const std::vector<int64_t>& dims, const std::vector<int64_t>& v) {
    auto* t = g_->add_initializer();
    t->set_name(name);
    t->set_data_type(onnx::TensorProto_DataType_INT64);
    for (int64_t d : dims) t->add_dims(d);
    t->set_raw_data(std::string(reinterpret_cast<const char*>(v.data()), v.size() * 8));
  }
  std::string save() {
    static int counter = 0;
    std::string path = "/tmp/isegman_onnx_test_" + std::to_string(getpid()) + "_" + std::to_string(counter++) + ".onnx";
    std::ofstream o(path, std::ios::binary);
    m_.SerializeToOstream(&o);
    return path;
  }

 private:
  onnx::ModelProto m_;
  onnx::GraphProto* g_;
};

void attr_int(onnx::NodeProto* n, const std::string& name, int64_t v) {
  auto* a = n->add_attribute();
  a->set_name(name);
  a->set_type(onnx::AttributeProto_AttributeType_INT);
  a->set_i(v);
}
void attr_ints(onnx::NodeProto* n, const std::string& name, const std::vector<int64_t>& v) {
  auto* a = n->add_attribute();
  a->set_name(name);
  a->set_type(onnx::AttributeProto_AttributeType_INTS);
  for (int64_t x : v) a->add_ints(x);
}
void attr_string(onnx::NodeProto* n, const std::string& name, const std::string& v) {
  auto* a = n->add_attribute();
  a->set_name(name);
  a->set_type(onnx::AttributeProto_AttributeType_STRING);
  a->set_s(v);
}

std::vector<float> floats_of(const HostTensor& t) { return {t.data<float>(), t.data<float>() + t.numel()}; }
std::vector<int64_t> ints_of(const HostTensor& t) { return {t.data<int64_t>(), t.data<int64_t>() + t.numel()}; }

struct Graph {
  std::string path;
  std::unique_ptr<OnnxGraph> g;
  explicit Graph(Builder& b) : path(b.save()), g(std::make_unique<OnnxGraph>(path)) {}
  ~Graph() { std::remove(path.c_str()); }
};

}  // namespace

TEST(OnnxGraph, UnsupportedOperatorNamesTheNode) {
  Builder b;
  b.input("x", {2});
  b.output("y");
  b.node("FancyNewOp", {"x"}, {"y"}, "my_fancy_node");
  std::string path = b.save();
  try {
    OnnxGraph g(path);
    FAIL() << "loaded a graph with an unknown operator";
  } catch (const Error& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("my_fancy_node"), std::string::npos) << msg;
    EXPECT_NE(msg.find("FancyNewOp"), std::string::npos) << msg;
    EXPECT_NE(msg.find("unsupported"), std::string::npos) << msg;
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
  }
  std::remove(path.c_str());
}

TEST(OnnxGraph, ShapeMismatchNamesTheNodeAndShapes) {
  Builder b;
  b.input("x", {-1, 3});
  b.floats("w", {4, 2}, std::vector<float>(8, 1.f));
  b.output("y");
  b.node("MatMul", {"x", "w"}, {"y"}, "projection");
  Graph g(b);
  try {
    g.g->run({{"x", HostTensor::from_floats({2, 3}, std::vector<float>(6, 1.f))}});
    FAIL() << "no error";
  } catch (const Error& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("projection"), std::string::npos) << msg;
    EXPECT_NE(msg.find("[2,3]"), std::string::npos) << msg;
    EXPECT_NE(msg.find("[4,2]"), std::string::npos) << msg;
  }
  EXPECT_THROW(g.g->run({}), Error);  // missing input
}

TEST(OnnxGraph, DynamicShapesThroughShapeArithmetic) {
  // y = Reshape(x, [Shape(x)[0], -1]) @ w, for any batch size.
  Builder b(13);
  b.input("x", {-1, 2, 2});
  b.floats("w", {4, 1}, {1, 2, 3, 4});
  b.ints("zero", {1}, {0});
  b.ints("minus_one", {1}, {-1});
  b.output("y");
  b.node("Shape", {"x"}, {"s"});
  attr_int(b.node("Gather", {"s", "zero"}, {"n"}), "axis", 0);
  attr_int(b.node("Concat", {"n", "minus_one"}, {"shape"}), "axis", 0);
  b.node("Reshape", {"x", "shape"}, {"flat"});
  b.node("MatMul", {"flat", "w"}, {"y"});
  Graph g(b);
  for (int n : {1, 3}) {
    std::vector<float> x(size_t(n) * 4);
    for (size_t i = 0; i < x.size(); ++i) x[i] = float(i);
    auto out = g.g->run({{"x", HostTensor::from_floats({n, 2, 2}, x)}});
    ASSERT_EQ(out["y"].shape, (std::vector<int64_t>{n, 1}));
    for (int r = 0; r < n; ++r)
      EXPECT_FLOAT_EQ(out["y"].data<float>()[r], x[r * 4] * 1 + x[r * 4 + 1] * 2 + x[r * 4 + 2] * 3 + x[r * 4 + 3] * 4);
  }
}

TEST(OnnxGraph, FoldsConstantSubgraphs) {
  Builder b(13);
  b.input("x", {3});
  b.floats("c", {3}, {1, 2, 3});
  b.output("y");
  b.node("Mul", {"c", "c"}, {"c2"});  // constant: folded at load
  b.node("Neg", {"c2"}, {"c3"});      // constant: folded at load
  b.node("Add", {"x", "c3"}, {"y"});
  Graph g(b);
  EXPECT_EQ(g.g->node_count(), 1u);
  EXPECT_EQ(g.g->op_types(), std::vector<std::string>{"Add"});
  auto out = g.g->run({{"x", HostTensor::from_floats({3}, {10, 10, 10})}});
  EXPECT_EQ(floats_of(out["y"]), (std::vector<float>{9, 6, 1}));
}

TEST(OnnxGraph, SliceClampsAndSteps) {
  Builder b(13);
  b.input("x", {6});
  b.ints("starts", {1}, {-1});
  b.ints("ends", {1}, {-100});
  b.ints("axes", {1}, {0});
  b.ints("steps", {1}, {-2});
  b.ints("s2", {1}, {2});
  b.ints("e2", {1}, {INT64_MAX});
  b.output("rev");
  b.output("tail");
  b.node("Slice", {"x", "starts", "ends", "axes", "steps"}, {"rev"});
  b.node("Slice", {"x", "s2", "e2"}, {"tail"});
  Graph g(b);
  auto out = g.g->run({{"x", HostTensor::from_floats({6}, {0, 1, 2, 3, 4, 5})}});
  EXPECT_EQ(floats_of(out["rev"]), (std::vector<float>{5, 3, 1}));
  EXPECT_EQ(floats_of(out["tail"]), (std::vector<float>{2, 3, 4, 5}));
}

TEST(OnnxGraph, GatherWithNegativeAndScalarIndices) {
  Builder b(13);
  b.input("x", {2, 3});
  b.ints("idx", {2}, {-1, 0});
  b.ints("one", {}, {1});
  b.output("cols");
  b.output("row");
  attr_int(b.node("Gather", {"x", "idx"}, {"cols"}), "axis", 1);
  attr_int(b.node("Gather", {"x", "one"}, {"row"}), "axis", 0);
  Graph g(b);
  auto out = g.g->run({{"x", HostTensor::from_floats({2, 3}, {0, 1, 2, 3, 4, 5})}});
  EXPECT_EQ(out["cols"].shape, (std::vector<int64_t>{2, 2}));
  EXPECT_EQ(floats_of(out["cols"]), (std::vector<float>{2, 0, 5, 3}));
  EXPECT_EQ(out["row"].shape, (std::vector<int64_t>{3}));
  EXPECT_EQ(floats_of(out["row"]), (std::vector<float>{3, 4, 5}));
}

TEST(OnnxGraph, ResizeLinearHalfPixel) {
  Builder b(17);
  b.input("x", {1, 1, 1, 2});
  b.ints("sizes", {4}, {1, 1, 1, 4});
  b.output("y");
  auto* n = b.node("Resize", {"x", "", "", "sizes"}, {"y"});
  attr_string(n, "mode", "linear");
  attr_string(n, "coordinate_transformation_mode", "half_pixel");
  Graph g(b);
  auto out = g.g->run({{"x", HostTensor::from_floats({1, 1, 1, 2}, {0, 1})}});
  std::vector<float> y = floats_of(out["y"]);
  std::vector<float> want = {0, 0.25f, 0.75f, 1};
  ASSERT_EQ(y.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(y[i], want[i], 1e-6);
}

TEST(OnnxGraph, SoftmaxBeforeOpset13FlattensAtTheAxis) {
  Builder b(12);
  b.input("x", {1, 2, 2});
  b.output("y");
  attr_int(b.node("Softmax", {"x"}, {"y"}), "axis", 1);
  Graph g(b);
  auto out = g.g->run({{"x", HostTensor::from_floats({1, 2, 2}, {0, 1, 2, 3})}});
  std::vector<float> y = floats_of(out["y"]);
  double z = 1 + std::exp(1.0) + std::exp(2.0) + std::exp(3.0);  // one softmax over all four
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(y[i], std::exp(double(i)) / z, 1e-6);
}

TEST(OnnxGraph, ConvWithAsymmetricPadsAndGroups) {
  // Two channels, depthwise 1x2 kernels, pads (left 1, right 0).
  Builder b(13);
  b.input("x", {1, 2, 1, 3});
  b.floats("w", {2, 1, 1, 2}, {1, 10, 2, 20});
  b.floats("bias", {2}, {0.5f, -0.5f});
  b.output("y");
  auto* n = b.node("Conv", {"x", "w", "bias"}, {"y"});
  attr_int(n, "group", 2);
  attr_ints(n, "pads", {0, 1, 0, 0});
  attr_ints(n, "kernel_shape", {1, 2});
  Graph g(b);
  auto out = g.g->run({{"x", HostTensor::from_floats({1, 2, 1, 3}, {1, 2, 3, 4, 5, 6})}});
  ASSERT_EQ(out["y"].shape, (std::vector<int64_t>{1, 2, 1, 3}));
  // channel 0 padded: [0,1,2,3] -> 1*a + 10*b over pairs; channel 1: [0,4,5,6] with 2, 20.
  std::vector<float> want = {10.5f, 21.5f, 32.5f, 79.5f, 107.5f, 129.5f};
  EXPECT_EQ(floats_of(out["y"]), want);
}

TEST(OnnxGraph, ExpandOneHotWhereRange) {
  Builder b(13);
  b.input("x", {3, 1});
  b.ints("shape", {2}, {1, 2});
  b.ints("labels", {3}, {0, -1, 1});
  b.ints("depth", {}, {3});
  b.floats("onoff", {2}, {0, 7});
  b.ints("r0", {}, {2});
  b.ints("r1", {}, {9});
  b.ints("r2", {}, {3});
  b.output("expanded");
  b.output("hot");
  b.output("picked");
  b.output("range");
  b.node("Expand", {"x", "shape"}, {"expanded"});  // [3,1] with [1,2] -> [3,2]
  b.node("OneHot", {"labels", "depth", "onoff"}, {"hot"});
  b.node("Greater", {"hot", "x"}, {"mask"});
  b.node("Where", {"mask", "hot", "x"}, {"picked"});
  b.node("Range", {"r0", "r1", "r2"}, {"range"});
  Graph g(b);
  auto out = g.g->run({{"x", HostTensor::from_floats({3, 1}, {1, 2, 3})}});
  EXPECT_EQ(out["expanded"].shape, (std::vector<int64_t>{3, 2}));
  EXPECT_EQ(floats_of(out["expanded"]), (std::vector<float>{1, 1, 2, 2, 3, 3}));
  EXPECT_EQ(floats_of(out["hot"]), (std::vector<float>{7, 0, 0, 0, 0, 7, 0, 7, 0}));  // -1 wraps to depth-1
  EXPECT_EQ(floats_of(out["picked"]), (std::vector<float>{7, 1, 1, 2, 2, 7, 3, 7, 3}));
  EXPECT_EQ(ints_of(out["range"]), (std::vector<int64_t>{2, 5, 8}));
}

// ---------------------------------------------------------------- kernels and fusions

namespace {

// Pseudo-random values in [-2, 2) from a fixed linear congruential sequence.
std::vector<float> noise(int64_t n, uint32_t seed) {
  std::vector<float> v(static_cast<size_t>(n));
  uint32_t s = seed * 2654435761u + 1u;
  for (auto& x : v) {
    s = s * 1664525u + 1013904223u;
    x = float(s >> 8) / float(1 << 24) * 4.0f - 2.0f;
  }
  return v;
}

int64_t count_of(const std::vector<int64_t>& dims) {
  int64_t n = 1;
  for (int64_t d : dims) n *= d;
  return n;
}

HostTensor random_tensor(const std::vector<int64_t>& dims, uint32_t seed) {
  return HostTensor::from_floats(dims, noise(count_of(dims), seed));
}

// One model loaded twice, with the fusion pass and with ISEGMAN_ONNX_NO_FUSION=1.
struct FusedAndPlain {
  std::string path;
  std::unique_ptr<OnnxGraph> fused, plain;
  explicit FusedAndPlain(Builder& b) : path(b.save()) {
    const char* was = std::getenv("ISEGMAN_ONNX_NO_FUSION");
    std::string saved = was ? was : "";
    unsetenv("ISEGMAN_ONNX_NO_FUSION");
    fused = std::make_unique<OnnxGraph>(path);
    setenv("ISEGMAN_ONNX_NO_FUSION", "1", 1);
    plain = std::make_unique<OnnxGraph>(path);
    if (was) setenv("ISEGMAN_ONNX_NO_FUSION", saved.c_str(), 1);
    else unsetenv("ISEGMAN_ONNX_NO_FUSION");
  }
  ~FusedAndPlain() { std::remove(path.c_str()); }
  bool has_op(const std::string& op) const {
    auto ops = fused->op_types();
    return std::find(ops.begin(), ops.end(), op) != ops.end();
  }
};

void expect_close(const HostTensor& a, const HostTensor& b, double tol) {
  ASSERT_EQ(a.shape, b.shape);
  std::vector<float> x = floats_of(a), y = floats_of(b);
  double worst = 0;
  for (size_t i = 0; i < x.size(); ++i) worst = std::max(worst, std::fabs(double(x[i]) - double(y[i])));
  EXPECT_LT(worst, tol);
}

}  // namespace

// MatMul on strided (transposed) operands with broadcast batch axes, against plain loops.
TEST(OnnxGraph, MatMulBroadcastsBatchesAndReadsTransposedOperands) {
  Builder b;
  b.input("a", {2, 1, 4, 3});  // transposed to [2,1,3,4]
  b.input("b", {5, 2, 4});     // transposed to [5,4,2]
  b.output("c");
  attr_ints(b.node("Transpose", {"a"}, {"at"}), "perm", {0, 1, 3, 2});
  attr_ints(b.node("Transpose", {"b"}, {"bt"}), "perm", {0, 2, 1});
  b.node("MatMul", {"at", "bt"}, {"c"});
  Graph g(b);
  std::vector<float> a = noise(2 * 4 * 3, 1), bv = noise(5 * 2 * 4, 2);
  auto out = g.g->run({{"a", HostTensor::from_floats({2, 1, 4, 3}, a)}, {"b", HostTensor::from_floats({5, 2, 4}, bv)}});
  ASSERT_EQ(out["c"].shape, (std::vector<int64_t>{2, 5, 3, 2}));
  std::vector<float> c = floats_of(out["c"]);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 5; ++j)
      for (int r = 0; r < 3; ++r)
        for (int col = 0; col < 2; ++col) {
          double want = 0;
          for (int k = 0; k < 4; ++k) want += double(a[size_t((i * 4 + k) * 3 + r)]) * double(bv[size_t((j * 2 + col) * 4 + k)]);
          EXPECT_NEAR(c[size_t(((i * 5 + j) * 3 + r) * 2 + col)], want, 1e-4);
        }
}

// An output the caller never reads is not returned, and the nodes only it needs are not
// run; a value needed by both outputs still is. Naming an output the graph lacks is an error.
TEST(OnnxGraph, UnreadOutputsAndTheNodesOnlyTheyNeedAreDropped) {
  Builder b;
  b.input("x", {2});
  b.floats("one", {1}, {1.f});
  b.output("y");
  b.output("z");
  b.node("Add", {"x", "one"}, {"shared"});
  b.node("Neg", {"shared"}, {"y"});
  b.node("Exp", {"shared"}, {"e"});
  b.node("Mul", {"e", "e"}, {"z"});
  const std::string path = b.save();
  auto unread_z = [](const OnnxModel&) { return OnnxGraph::OutputChoice{{}, {"z"}}; };
  OnnxGraph all(path), some(path, unread_z);
  EXPECT_EQ(all.node_count(), 4u);
  EXPECT_EQ(some.node_count(), 2u);  // Add and Neg
  EXPECT_EQ(some.outputs().size(), 2u);  // still declared
  auto out = some.run({{"x", HostTensor::from_floats({2}, {1, 2})}});
  EXPECT_EQ(out.count("z"), 0u);
  EXPECT_EQ(floats_of(out.at("y")), (std::vector<float>{-2, -3}));
  EXPECT_THROW(OnnxGraph(path, [](const OnnxModel&) { return OnnxGraph::OutputChoice{{}, {"nope"}}; }), Error);
  std::remove(path.c_str());
}

// A large swap of the last two axes is copied by the executor's blocked kernel (sizes
// that are not multiples of its block, two batch items): the same values as the view.
TEST(OnnxGraph, LargeTransposeOfTheLastTwoAxes) {
  const int64_t b = 2, m = 37, n = 2003;  // 148,222 values: above the copy's threshold
  Builder g;
  g.input("x", {b, m, n});
  g.output("y");
  attr_ints(g.node("Transpose", {"x"}, {"y"}), "perm", {0, 2, 1});
  Graph graph(g);
  std::vector<float> x = noise(b * m * n, 5);
  auto out = graph.g->run({{"x", HostTensor::from_floats({b, m, n}, x)}});
  ASSERT_EQ(out["y"].shape, (std::vector<int64_t>{b, n, m}));
  std::vector<float> y = floats_of(out["y"]);
  size_t wrong = 0;
  for (int64_t k = 0; k < b; ++k)
    for (int64_t i = 0; i < m; ++i)
      for (int64_t j = 0; j < n; ++j) wrong += y[size_t((k * n + j) * m + i)] != x[size_t((k * m + i) * n + j)];
  EXPECT_EQ(wrong, 0u);
}

// SAM's output upscaling: ConvTranspose with kernel = stride, on an NCHW input and on a
// transposed NHWC view (as the decoder feeds it), against the definition summed here.
TEST(OnnxGraph, ConvTransposeWithKernelEqualToStride) {
  const int n = 2, ci = 3, h = 2, w = 3, co = 2, k = 2;
  for (bool nhwc : {false, true}) {
    Builder b;
    std::vector<float> x = noise(n * ci * h * w, 3), wt = noise(ci * co * k * k, 4), bias = {0.25f, -1.5f};
    if (nhwc) {
      b.input("x", {n, h, w, ci});
      attr_ints(b.node("Transpose", {"x"}, {"xt"}), "perm", {0, 3, 1, 2});
    } else {
      b.input("xt", {n, ci, h, w});
    }
    b.floats("w", {ci, co, k, k}, wt);
    b.floats("bias", {co}, bias);
    b.output("y");
    auto* node = b.node("ConvTranspose", {"xt", "w", "bias"}, {"y"});
    attr_ints(node, "strides", {k, k});
    attr_ints(node, "kernel_shape", {k, k});
    Graph g(b);
    auto out = g.g->run({{nhwc ? "x" : "xt", HostTensor::from_floats(nhwc ? std::vector<int64_t>{n, h, w, ci}
                                                                           : std::vector<int64_t>{n, ci, h, w},
                                                                      x)}});
    ASSERT_EQ(out["y"].shape, (std::vector<int64_t>{n, co, h * k, w * k}));
    std::vector<float> y = floats_of(out["y"]);
    auto in = [&](int b_, int c, int i, int j) {
      return double(nhwc ? x[size_t(((b_ * h + i) * w + j) * ci + c)] : x[size_t(((b_ * ci + c) * h + i) * w + j)]);
    };
    for (int b_ = 0; b_ < n; ++b_)
      for (int o = 0; o < co; ++o)
        for (int yy = 0; yy < h * k; ++yy)
          for (int xx = 0; xx < w * k; ++xx) {
            double want = bias[size_t(o)];
            for (int c = 0; c < ci; ++c)
              want += in(b_, c, yy / k, xx / k) * double(wt[size_t(((c * co + o) * k + yy % k) * k + xx % k)]);
            EXPECT_NEAR(y[size_t(((b_ * co + o) * h * k + yy) * w * k + xx)], want, 1e-5) << (nhwc ? "NHWC" : "NCHW");
          }
  }
}

// A 1x1 convolution runs over blocks of 256 pixels: two images of 17 x 19 pixels (one full
// block and a partial one each), with and without a bias, on an NCHW input and on a
// transposed NHWC view (read in place), against the definition summed here.
TEST(OnnxGraph, Conv1x1OverPixelBlocks) {
  const int n = 2, ci = 5, h = 17, w = 19, co = 7;
  for (bool nhwc : {false, true})
    for (bool with_bias : {true, false}) {
      Builder b;
      std::vector<float> x = noise(n * ci * h * w, 5), wt = noise(co * ci, 6), bias = noise(co, 7);
      if (nhwc) {
        b.input("x", {n, h, w, ci});
        attr_ints(b.node("Transpose", {"x"}, {"xt"}), "perm", {0, 3, 1, 2});
      } else {
        b.input("xt", {n, ci, h, w});
      }
      b.floats("w", {co, ci, 1, 1}, wt);
      if (with_bias) b.floats("bias", {co}, bias);
      b.output("y");
      auto* node = b.node("Conv", with_bias ? std::vector<std::string>{"xt", "w", "bias"} : std::vector<std::string>{"xt", "w"},
                          {"y"});
      attr_ints(node, "kernel_shape", {1, 1});
      Graph g(b);
      auto out = g.g->run({{nhwc ? "x" : "xt", HostTensor::from_floats(nhwc ? std::vector<int64_t>{n, h, w, ci}
                                                                             : std::vector<int64_t>{n, ci, h, w},
                                                                        x)}});
      ASSERT_EQ(out["y"].shape, (std::vector<int64_t>{n, co, h, w}));
      const std::vector<float> y = floats_of(out["y"]);
      size_t wrong = 0;
      for (int b_ = 0; b_ < n; ++b_)
        for (int o = 0; o < co; ++o)
          for (int p = 0; p < h * w; ++p) {
            double want = with_bias ? bias[size_t(o)] : 0.0;
            for (int c = 0; c < ci; ++c)
              want += double(wt[size_t(o * ci + c)]) *
                      double(nhwc ? x[size_t((b_ * h * w + p) * ci + c)] : x[size_t((b_ * ci + c) * h * w + p)]);
            wrong += std::fabs(y[size_t((b_ * co + o) * h * w + p)] - want) > 1e-5;
          }
      EXPECT_EQ(wrong, 0u) << (nhwc ? "NHWC" : "NCHW") << (with_bias ? ", bias" : ", no bias");
    }
}

// Depthwise 3x3 convolutions (TinyViT's): the rows whose taps all lie inside the image sum
// their nine taps at once. Against the definition, with stride 1 and 2, with and without
// padding, and rows too narrow for any inner column.
TEST(OnnxGraph, DepthwiseThreeByThreeConvolution) {
  struct Case {
    int h, w, stride, pad;
  };
  for (const Case& k : {Case{7, 9, 1, 1}, Case{8, 8, 2, 1}, Case{5, 2, 1, 1}, Case{6, 5, 1, 0}, Case{9, 11, 2, 0}}) {
    const int n = 2, ch = 3;
    Builder b;
    std::vector<float> x = noise(n * ch * k.h * k.w, 8), wt = noise(ch * 9, 9), bias = noise(ch, 10);
    b.input("x", {n, ch, k.h, k.w});
    b.floats("w", {ch, 1, 3, 3}, wt);
    b.floats("bias", {ch}, bias);
    b.output("y");
    auto* node = b.node("Conv", {"x", "w", "bias"}, {"y"});
    attr_int(node, "group", ch);
    attr_ints(node, "kernel_shape", {3, 3});
    attr_ints(node, "strides", {k.stride, k.stride});
    attr_ints(node, "pads", {k.pad, k.pad, k.pad, k.pad});
    Graph g(b);
    auto out = g.g->run({{"x", HostTensor::from_floats({n, ch, k.h, k.w}, x)}});
    const int oh = (k.h + 2 * k.pad - 3) / k.stride + 1, ow = (k.w + 2 * k.pad - 3) / k.stride + 1;
    ASSERT_EQ(out["y"].shape, (std::vector<int64_t>{n, ch, oh, ow}));
    const std::vector<float> y = floats_of(out["y"]);
    size_t wrong = 0;
    for (int b_ = 0; b_ < n; ++b_)
      for (int c = 0; c < ch; ++c)
        for (int oy = 0; oy < oh; ++oy)
          for (int ox = 0; ox < ow; ++ox) {
            double want = bias[size_t(c)];
            for (int ky = 0; ky < 3; ++ky)
              for (int kx = 0; kx < 3; ++kx) {
                const int iy = oy * k.stride - k.pad + ky, ix = ox * k.stride - k.pad + kx;
                if (iy >= 0 && iy < k.h && ix >= 0 && ix < k.w)
                  want += double(wt[size_t(c * 9 + ky * 3 + kx)]) * double(x[size_t(((b_ * ch + c) * k.h + iy) * k.w + ix)]);
              }
            wrong += std::fabs(y[size_t(((b_ * ch + c) * oh + oy) * ow + ox)] - want) > 1e-5;
          }
    EXPECT_EQ(wrong, 0u) << k.h << "x" << k.w << " stride " << k.stride << " pad " << k.pad;
  }
}

// TinyViT's window attention (opset 12): MatMul(q, kT) -> Mul(scale) -> Add(bias) ->
// Softmax(axis 3) -> MatMul(v) becomes one FusedAttention step with the same result.
TEST(OnnxGraph, FusesWindowAttentionWithScaleAndBias) {
  Builder b(12);
  b.input("q", {6, 4, 7, 8});
  b.input("k", {6, 4, 7, 8});
  b.input("v", {6, 4, 7, 8});
  b.floats("scale", {}, {0.35f});
  b.floats("bias", {4, 7, 7}, noise(4 * 7 * 7, 3));
  b.output("y");
  attr_ints(b.node("Transpose", {"k"}, {"kt"}), "perm", {0, 1, 3, 2});
  b.node("MatMul", {"q", "kt"}, {"s"});
  b.node("Mul", {"s", "scale"}, {"ss"});
  b.node("Add", {"ss", "bias"}, {"sb"});
  attr_int(b.node("Softmax", {"sb"}, {"p"}), "axis", 3);
  b.node("MatMul", {"p", "v"}, {"y"});
  FusedAndPlain g(b);
  EXPECT_TRUE(g.has_op("FusedAttention"));
  EXPECT_EQ(g.fused->node_count() + 4, g.plain->node_count());
  std::map<std::string, HostTensor> feeds = {
      {"q", random_tensor({6, 4, 7, 8}, 4)}, {"k", random_tensor({6, 4, 7, 8}, 5)}, {"v", random_tensor({6, 4, 7, 8}, 6)}};
  expect_close(g.fused->run(feeds)["y"], g.plain->run(feeds)["y"], 1e-5);
}

// The SAM decoder's form: the divisor is computed at run time (sqrt of a shape), no bias,
// and score rows longer than one cache block (the kernel splits the rows of an item).
TEST(OnnxGraph, FusesAttentionWithRuntimeDivisorAndLongRows) {
  Builder b(17);
  b.input("q", {1, 2, 40, 16});
  b.input("k", {1, 2, 600, 16});
  b.input("v", {1, 2, 600, 8});
  b.ints("last", {}, {3});
  b.output("y");
  b.node("Shape", {"q"}, {"qs"});
  attr_int(b.node("Gather", {"qs", "last"}, {"width"}), "axis", 0);
  attr_int(b.node("Cast", {"width"}, {"widthf"}), "to", onnx::TensorProto_DataType_FLOAT);
  b.node("Sqrt", {"widthf"}, {"root"});
  attr_ints(b.node("Transpose", {"k"}, {"kt"}), "perm", {0, 1, 3, 2});
  b.node("MatMul", {"q", "kt"}, {"s"});
  b.node("Div", {"s", "root"}, {"sd"});
  attr_int(b.node("Softmax", {"sd"}, {"p"}), "axis", -1);
  b.node("MatMul", {"p", "v"}, {"y"});
  FusedAndPlain g(b);
  EXPECT_TRUE(g.has_op("FusedAttention"));
  std::map<std::string, HostTensor> feeds = {
      {"q", random_tensor({1, 2, 40, 16}, 7)}, {"k", random_tensor({1, 2, 600, 16}, 8)}, {"v", random_tensor({1, 2, 600, 8}, 9)}};
  expect_close(g.fused->run(feeds)["y"], g.plain->run(feeds)["y"], 1e-5);
}

// SAM decoder's attentions: heads of 16 values interleaved in the tokens' rows (row stride
// heads x 16), few queries over many keys and many queries over few keys; the fused step
// gives what the plain operators give.
TEST(OnnxGraph, FusedAttentionOverInterleavedHeads) {
  for (auto [queries, keys] : {std::pair<int64_t, int64_t>{9, 700}, {700, 9}}) {
    const int64_t heads = 4, dim = 16, vdim = 12;
    Builder b(17);
    b.input("q", {1, queries, heads, dim});
    b.input("k", {1, keys, heads, dim});
    b.input("v", {1, keys, heads, vdim});
    b.floats("scale", {}, {0.25f});
    b.output("y");
    attr_ints(b.node("Transpose", {"q"}, {"qh"}), "perm", {0, 2, 1, 3});
    attr_ints(b.node("Transpose", {"k"}, {"kt"}), "perm", {0, 2, 3, 1});
    attr_ints(b.node("Transpose", {"v"}, {"vh"}), "perm", {0, 2, 1, 3});
    b.node("MatMul", {"qh", "kt"}, {"s"});
    b.node("Mul", {"s", "scale"}, {"ss"});
    attr_int(b.node("Softmax", {"ss"}, {"p"}), "axis", -1);
    b.node("MatMul", {"p", "vh"}, {"y"});
    FusedAndPlain g(b);
    EXPECT_TRUE(g.has_op("FusedAttention"));
    std::map<std::string, HostTensor> feeds = {{"q", random_tensor({1, queries, heads, dim}, 11)},
                                               {"k", random_tensor({1, keys, heads, dim}, 12)},
                                               {"v", random_tensor({1, keys, heads, vdim}, 13)}};
    expect_close(g.fused->run(feeds)["y"], g.plain->run(feeds)["y"], 1e-5);
  }
}

// Softmax before opset 13 flattens the axes from `axis` on: over axis 1 of a rank-4 score
// tensor that is not the attention softmax, and the fused step must give what the plain
// operators give.
TEST(OnnxGraph, FusedAttentionKeepsSoftmaxOverOtherAxes) {
  Builder b(12);
  b.input("q", {2, 3, 5, 4});
  b.input("kt", {2, 3, 4, 5});
  b.input("v", {2, 3, 5, 4});
  b.output("y");
  b.node("MatMul", {"q", "kt"}, {"s"});
  attr_int(b.node("Softmax", {"s"}, {"p"}), "axis", 1);
  b.node("MatMul", {"p", "v"}, {"y"});
  FusedAndPlain g(b);
  EXPECT_TRUE(g.has_op("FusedAttention"));
  std::map<std::string, HostTensor> feeds = {
      {"q", random_tensor({2, 3, 5, 4}, 10)}, {"kt", random_tensor({2, 3, 4, 5}, 11)}, {"v", random_tensor({2, 3, 5, 4}, 12)}};
  expect_close(g.fused->run(feeds)["y"], g.plain->run(feeds)["y"], 1e-5);
}

// Large intermediates come from the tensor pool, and a second run reuses its blocks
// instead of mapping (and page-faulting) fresh memory.
TEST(TensorMemory, SecondRunReusesLargeBlocks) {
  if (std::getenv("ISEGMAN_ONNX_NO_POOL")) GTEST_SKIP() << "ISEGMAN_ONNX_NO_POOL is set";
  Builder b;
  b.input("x", {512, 1024});  // 2 MiB per tensor
  b.output("y");
  b.node("Mul", {"x", "x"}, {"sq"});
  b.node("Add", {"sq", "x"}, {"s"});
  b.node("Relu", {"s"}, {"y"});
  Graph g(b);
  HostTensor x = random_tensor({512, 1024}, 13);
  g.g->run({{"x", x}});
  size_t maps = tensor_memory_pool_mappings();
  EXPECT_GT(maps, 0u);
  EXPECT_GT(tensor_memory_pool_cached_bytes(), 0u);
  auto out = g.g->run({{"x", x}});
  EXPECT_EQ(tensor_memory_pool_mappings(), maps);
  std::vector<float> xv = floats_of(x), y = floats_of(out["y"]);
  for (size_t i = 0; i < y.size(); i += 4099) EXPECT_NEAR(y[i], std::max(0.0f, xv[i] * xv[i] + xv[i]), 1e-5);
  // Trimmed, the pool keeps nothing; the next run maps afresh and computes the same.
  EXPECT_GT(trim_tensor_memory_pool(), 0u);
  EXPECT_EQ(tensor_memory_pool_cached_bytes(), 0u);
  auto again = g.g->run({{"x", x}});
  EXPECT_GT(tensor_memory_pool_mappings(), maps);
  EXPECT_EQ(floats_of(again["y"]), y);
}

// An empty inner axis: the product is all zeros (and Gemm adds its C).
TEST(OnnxGraph, MatMulAndGemmWithEmptyInnerAxis) {
  Builder b;
  b.input("a", {2, 0});
  b.input("b", {0, 3});
  b.floats("c", {3}, {1, 2, 3});
  b.output("y");
  b.output("z");
  b.node("MatMul", {"a", "b"}, {"y"});
  b.node("Gemm", {"a", "b", "c"}, {"z"});
  Graph g(b);
  auto out = g.g->run({{"a", HostTensor::from_floats({2, 0}, {})}, {"b", HostTensor::from_floats({0, 3}, {})}});
  EXPECT_EQ(floats_of(out["y"]), (std::vector<float>(6, 0.0f)));
  EXPECT_EQ(floats_of(out["z"]), (std::vector<float>{1, 2, 3, 1, 2, 3}));
}

// Values computed from some inputs alone are kept and reused: the rest of the graph gives
// what a whole run gives, shape arithmetic of the other inputs is checked, and the inputs
// are checked.
TEST(OnnxGraph, StableValuesAreComputedOnceAndReused) {
  Builder b(13);
  b.input("x", {3});
  b.input("y", {-1});
  b.floats("c", {3}, {1, 2, 3});
  b.ints("zero", {}, {0});
  b.ints("axes", {1}, {0});
  b.output("sum");
  b.output("only_x");
  b.node("Mul", {"x", "c"}, {"xc"});          // from x alone
  b.node("Neg", {"xc"}, {"only_x"});          // from x alone, and an output
  b.node("Shape", {"y"}, {"ys"});             // shape arithmetic of y ...
  b.node("Gather", {"ys", "zero"}, {"n"});
  b.node("Unsqueeze", {"n", "axes"}, {"reps"});
  b.node("Tile", {"xc", "reps"}, {"tiled"});  // ... that a kept step reads
  attr_int(b.node("Concat", {"y", "y", "y"}, {"yyy"}), "axis", 0);
  b.node("Add", {"tiled", "yyy"}, {"sum"});   // needs y's values
  Graph g(b);
  const HostTensor x = HostTensor::from_floats({3}, {1, -2, 0.5f});
  auto y_of = [](std::vector<float> v) { return HostTensor::from_floats({int64_t(v.size())}, v); };
  std::shared_ptr<const OnnxGraph::Stable> kept;
  auto first = g.g->run({{"x", x}, {"y", y_of({4, 5})}}, {"x"}, kept);
  auto whole = g.g->run({{"x", x}, {"y", y_of({4, 5})}});
  EXPECT_EQ(floats_of(first.at("sum")), floats_of(whole.at("sum")));
  EXPECT_EQ(floats_of(first.at("only_x")), floats_of(whole.at("only_x")));
  EXPECT_GT(OnnxGraph::stable_bytes(*kept), 0u);
  // Other values of y, same shape: from the kept values.
  for (int round = 0; round < 2; ++round) {
    auto part = g.g->run({{"y", y_of({0, 1})}}, *kept);
    auto ref = g.g->run({{"x", x}, {"y", y_of({0, 1})}});
    EXPECT_EQ(floats_of(part.at("sum")), floats_of(ref.at("sum")));
    EXPECT_EQ(floats_of(part.at("only_x")), floats_of(ref.at("only_x")));
  }
  EXPECT_EQ(floats_of(g.g->run({{"y", y_of({0, 0})}}, *kept).at("sum")),
            (std::vector<float>{1, -4, 1.5f, 1, -4, 1.5f}));
  EXPECT_EQ(OnnxGraph::whole_runs(*kept), 0u);
  // Another length of y tiles xc another number of times: the whole graph runs.
  auto longer = g.g->run({{"y", y_of({0, 0, 1})}}, *kept);
  EXPECT_EQ(OnnxGraph::whole_runs(*kept), 1u);
  EXPECT_EQ(floats_of(longer.at("sum")), floats_of(g.g->run({{"x", x}, {"y", y_of({0, 0, 1})}}).at("sum")));
  EXPECT_THROW(g.g->run({}, *kept), Error);                           // y missing
  EXPECT_THROW(g.g->run({{"x", x}, {"y", y_of({1, 2})}}, *kept), Error);  // x given twice
  std::shared_ptr<const OnnxGraph::Stable> none;
  EXPECT_THROW(g.g->run({{"x", x}, {"y", x}}, {"z"}, none), Error);   // no such input
  Graph g2(b);
  EXPECT_THROW(g2.g->run({{"y", x}}, *kept), Error);                  // another graph's values
}
