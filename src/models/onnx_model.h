// An ONNX model read into plain C++ structures (no protobuf, no libtorch in this header):
// the graph's nodes in file order (ONNX requires topological order), its attributes, its
// initialisers as host tensors, and the declared inputs and outputs.
#pragma once

#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace isegman::models {

enum class DType { Float32, Float64, Float16, Int8, UInt8, Int32, Int64, Bool };

const char* dtype_name(DType t);
size_t dtype_size(DType t);

// A dense row-major tensor in host memory. The bytes are shared (copying a HostTensor is
// cheap); mutate only tensors you created.
struct HostTensor {
  DType dtype = DType::Float32;
  std::vector<int64_t> shape;
  std::shared_ptr<std::vector<uint8_t>> bytes = std::make_shared<std::vector<uint8_t>>();

  HostTensor() = default;
  HostTensor(DType t, std::vector<int64_t> dims) : dtype(t), shape(std::move(dims)) {
    bytes->resize(numel() * dtype_size(t));
  }
  int64_t numel() const {
    int64_t n = 1;
    for (int64_t d : shape) n *= d;
    return n;
  }
  template <class T> T* data() { return reinterpret_cast<T*>(bytes->data()); }
  template <class T> const T* data() const { return reinterpret_cast<const T*>(bytes->data()); }

  static HostTensor from_floats(std::vector<int64_t> dims, const std::vector<float>& v);
  static HostTensor from_int64s(std::vector<int64_t> dims, const std::vector<int64_t>& v);
  // "float32[1,256,64,64]"
  std::string describe() const;
};

struct Attribute {
  enum class Kind { Int, Float, String, Ints, Floats, Strings, Tensor, Graph, Other };
  Kind kind = Kind::Other;
  int64_t i = 0;
  float f = 0;
  std::string s;
  std::vector<int64_t> ints;
  std::vector<float> floats;
  std::vector<std::string> strings;
  HostTensor t;
};

struct Node {
  std::string name, op_type, domain;
  std::vector<std::string> inputs, outputs;  // "" marks an omitted optional input/output
  std::map<std::string, Attribute> attrs;

  // "node 'name' (OpType)", the form every error about a node uses.
  std::string label() const;
  bool has(const std::string& a) const { return attrs.count(a) != 0; }
  int64_t get_int(const std::string& a, int64_t fallback) const;
  float get_float(const std::string& a, float fallback) const;
  std::string get_string(const std::string& a, const std::string& fallback) const;
  std::vector<int64_t> get_ints(const std::string& a, const std::vector<int64_t>& fallback) const;
};

struct ValueInfo {
  std::string name;
  DType dtype = DType::Float32;
  std::vector<int64_t> dims;          // -1 where dynamic
  std::vector<std::string> dim_names; // the symbolic name where dynamic, else ""
};

struct OnnxModel {
  std::string path;
  int64_t opset = 0;  // of the default ("" / "ai.onnx") domain
  std::vector<ValueInfo> inputs;   // graph inputs that are not initialisers
  std::vector<ValueInfo> outputs;
  std::map<std::string, HostTensor> initializers;
  std::vector<Node> nodes;
};

// Reads an .onnx file (external data files beside it are resolved). Throws isegman::Error
// naming the file on any problem.
OnnxModel load_onnx(const std::string& path);

}  // namespace isegman::models
