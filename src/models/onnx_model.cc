// Protobuf -> plain structures. This file includes the ONNX protobuf headers but never libtorch.
#include "models/onnx_model.h"

#include <climits>
#include <fstream>
#include <sstream>

#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/io/zero_copy_stream_impl.h>
#include <onnx/onnx_pb.h>

#include "core/error.h"

namespace isegman::models {

const char* dtype_name(DType t) {
  switch (t) {
    case DType::Float32: return "float32";
    case DType::Float64: return "float64";
    case DType::Float16: return "float16";
    case DType::Int8: return "int8";
    case DType::UInt8: return "uint8";
    case DType::Int32: return "int32";
    case DType::Int64: return "int64";
    case DType::Bool: return "bool";
  }
  return "?";
}

size_t dtype_size(DType t) {
  switch (t) {
    case DType::Float32: return 4;
    case DType::Float64: return 8;
    case DType::Float16: return 2;
    case DType::Int8: return 1;
    case DType::UInt8: return 1;
    case DType::Int32: return 4;
    case DType::Int64: return 8;
    case DType::Bool: return 1;
  }
  return 1;
}

HostTensor HostTensor::from_floats(std::vector<int64_t> dims, const std::vector<float>& v) {
  HostTensor t(DType::Float32, std::move(dims));
  if (size_t(t.numel()) != v.size()) throw Error("HostTensor::from_floats: size does not match the shape");
  std::memcpy(t.bytes->data(), v.data(), v.size() * 4);
  return t;
}

HostTensor HostTensor::from_int64s(std::vector<int64_t> dims, const std::vector<int64_t>& v) {
  HostTensor t(DType::Int64, std::move(dims));
  if (size_t(t.numel()) != v.size()) throw Error("HostTensor::from_int64s: size does not match the shape");
  std::memcpy(t.bytes->data(), v.data(), v.size() * 8);
  return t;
}

std::string HostTensor::describe() const {
  std::ostringstream s;
  s << dtype_name(dtype) << "[";
  for (size_t i = 0; i < shape.size(); ++i) s << (i ? "," : "") << shape[i];
  s << "]";
  return s.str();
}

std::string Node::label() const { return "node '" + name + "' (" + op_type + ")"; }

int64_t Node::get_int(const std::string& a, int64_t fallback) const {
  auto it = attrs.find(a);
  return it == attrs.end() ? fallback : it->second.i;
}
float Node::get_float(const std::string& a, float fallback) const {
  auto it = attrs.find(a);
  return it == attrs.end() ? fallback : it->second.f;
}
std::string Node::get_string(const std::string& a, const std::string& fallback) const {
  auto it = attrs.find(a);
  return it == attrs.end() ? fallback : it->second.s;
}
std::vector<int64_t> Node::get_ints(const std::string& a, const std::vector<int64_t>& fallback) const {
  auto it = attrs.find(a);
  return it == attrs.end() ? fallback : it->second.ints;
}

namespace {

DType convert_dtype(int t, const std::string& where) {
  switch (t) {
    case onnx::TensorProto_DataType_FLOAT: return DType::Float32;
    case onnx::TensorProto_DataType_DOUBLE: return DType::Float64;
    case onnx::TensorProto_DataType_FLOAT16: return DType::Float16;
    case onnx::TensorProto_DataType_INT8: return DType::Int8;
    case onnx::TensorProto_DataType_UINT8: return DType::UInt8;
    case onnx::TensorProto_DataType_INT32: return DType::Int32;
    case onnx::TensorProto_DataType_INT64: return DType::Int64;
    case onnx::TensorProto_DataType_BOOL: return DType::Bool;
    default: break;
  }
  throw Error(where, "unsupported tensor element type " + std::to_string(t));
}

std::string dir_of(const std::string& path) {
  size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

template <class Src, class Dst>
void copy_typed(const Src& src, HostTensor& t) {
  Dst* out = t.data<Dst>();
  for (int64_t i = 0; i < t.numel(); ++i) out[i] = static_cast<Dst>(src.Get(int(i)));
}

HostTensor convert_tensor(const onnx::TensorProto& p, const std::string& model_path) {
  std::string where = model_path + ": tensor '" + p.name() + "'";
  std::vector<int64_t> dims(p.dims().begin(), p.dims().end());
  HostTensor t(convert_dtype(p.data_type(), where), dims);
  size_t nbytes = size_t(t.numel()) * dtype_size(t.dtype);
  if (p.data_location() == onnx::TensorProto_DataLocation_EXTERNAL) {
    std::string location;
    int64_t offset = 0, length = -1;
    for (const auto& kv : p.external_data()) {
      if (kv.key() == "location") location = kv.value();
      else if (kv.key() == "offset") offset = std::stoll(kv.value());
      else if (kv.key() == "length") length = std::stoll(kv.value());
    }
    if (location.empty()) throw Error(where, "external data without a location");
    if (length >= 0 && size_t(length) != nbytes) throw Error(where, "external data length does not match its shape");
    std::string file = dir_of(model_path) + "/" + location;
    std::ifstream in(file, std::ios::binary);
    if (!in) throw Error(file, "cannot open external data file (of " + where + ")");
    in.seekg(offset);
    in.read(reinterpret_cast<char*>(t.bytes->data()), std::streamsize(nbytes));
    if (size_t(in.gcount()) != nbytes) throw Error(file, "external data file too short (for " + where + ")");
    return t;
  }
  if (p.has_raw_data()) {
    if (p.raw_data().size() != nbytes)
      throw Error(where, "raw data has " + std::to_string(p.raw_data().size()) + " bytes, shape needs " +
                             std::to_string(nbytes));
    std::memcpy(t.bytes->data(), p.raw_data().data(), nbytes);
    return t;
  }
  auto check = [&](int n) {
    if (n != t.numel()) throw Error(where, "typed data has " + std::to_string(n) + " values, shape needs " +
                                              std::to_string(t.numel()));
  };
  switch (t.dtype) {
    case DType::Float32: check(p.float_data_size()); copy_typed<decltype(p.float_data()), float>(p.float_data(), t); break;
    case DType::Float64: check(p.double_data_size()); copy_typed<decltype(p.double_data()), double>(p.double_data(), t); break;
    case DType::Int64: check(p.int64_data_size()); copy_typed<decltype(p.int64_data()), int64_t>(p.int64_data(), t); break;
    case DType::Int32: check(p.int32_data_size()); copy_typed<decltype(p.int32_data()), int32_t>(p.int32_data(), t); break;
    case DType::Int8: check(p.int32_data_size()); copy_typed<decltype(p.int32_data()), int8_t>(p.int32_data(), t); break;
    case DType::UInt8: check(p.int32_data_size()); copy_typed<decltype(p.int32_data()), uint8_t>(p.int32_data(), t); break;
    case DType::Bool: check(p.int32_data_size()); copy_typed<decltype(p.int32_data()), uint8_t>(p.int32_data(), t); break;
    case DType::Float16: check(p.int32_data_size()); copy_typed<decltype(p.int32_data()), uint16_t>(p.int32_data(), t); break;
  }
  return t;
}

ValueInfo convert_value_info(const onnx::ValueInfoProto& v, const std::string& model_path) {
  ValueInfo info;
  info.name = v.name();
  if (v.type().has_tensor_type()) {
    const auto& tt = v.type().tensor_type();
    try {
      info.dtype = convert_dtype(tt.elem_type(), model_path + ": value '" + v.name() + "'");
    } catch (const Error&) {
      info.dtype = DType::Float32;  // reported when the value is actually used
    }
    for (const auto& d : tt.shape().dim()) {
      info.dims.push_back(d.has_dim_value() ? d.dim_value() : -1);
      info.dim_names.push_back(d.has_dim_param() ? d.dim_param() : "");
    }
  }
  return info;
}

}  // namespace

OnnxModel load_onnx(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(path, "cannot open ONNX model file");
  onnx::ModelProto proto;
  {
    google::protobuf::io::IstreamInputStream raw(&file);
    google::protobuf::io::CodedInputStream coded(&raw);
    coded.SetTotalBytesLimit(INT_MAX);
    if (!proto.ParseFromCodedStream(&coded) || !proto.has_graph())
      throw Error(path, "not a valid ONNX model (protobuf parse failed)");
  }
  OnnxModel m;
  m.path = path;
  for (const auto& op : proto.opset_import())
    if (op.domain().empty() || op.domain() == "ai.onnx") m.opset = op.version();
  const auto& g = proto.graph();
  for (const auto& init : g.initializer()) m.initializers.emplace(init.name(), convert_tensor(init, path));
  for (const auto& in : g.input())
    if (!m.initializers.count(in.name())) m.inputs.push_back(convert_value_info(in, path));
  for (const auto& out : g.output()) m.outputs.push_back(convert_value_info(out, path));
  int index = 0;
  for (const auto& np : g.node()) {
    Node n;
    n.name = np.name().empty() ? np.op_type() + "_" + std::to_string(index) : np.name();
    n.op_type = np.op_type();
    n.domain = np.domain();
    n.inputs.assign(np.input().begin(), np.input().end());
    n.outputs.assign(np.output().begin(), np.output().end());
    for (const auto& ap : np.attribute()) {
      Attribute a;
      switch (ap.type()) {
        case onnx::AttributeProto_AttributeType_INT: a.kind = Attribute::Kind::Int; a.i = ap.i(); break;
        case onnx::AttributeProto_AttributeType_FLOAT: a.kind = Attribute::Kind::Float; a.f = ap.f(); break;
        case onnx::AttributeProto_AttributeType_STRING: a.kind = Attribute::Kind::String; a.s = ap.s(); break;
        case onnx::AttributeProto_AttributeType_INTS:
          a.kind = Attribute::Kind::Ints;
          a.ints.assign(ap.ints().begin(), ap.ints().end());
          break;
        case onnx::AttributeProto_AttributeType_FLOATS:
          a.kind = Attribute::Kind::Floats;
          a.floats.assign(ap.floats().begin(), ap.floats().end());
          break;
        case onnx::AttributeProto_AttributeType_STRINGS:
          a.kind = Attribute::Kind::Strings;
          a.strings.assign(ap.strings().begin(), ap.strings().end());
          break;
        case onnx::AttributeProto_AttributeType_TENSOR:
          a.kind = Attribute::Kind::Tensor;
          a.t = convert_tensor(ap.t(), path);
          break;
        case onnx::AttributeProto_AttributeType_GRAPH:
        case onnx::AttributeProto_AttributeType_GRAPHS: a.kind = Attribute::Kind::Graph; break;
        default: a.kind = Attribute::Kind::Other; break;
      }
      n.attrs[ap.name()] = std::move(a);
    }
    m.nodes.push_back(std::move(n));
    ++index;
  }
  return m;
}

}  // namespace isegman::models
