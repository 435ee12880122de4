// A small ONNX graph executor on libtorch (ATen) CPU tensors. Loads an .onnx file, folds
// every node whose inputs are constants once at load time, and runs the rest node by node
// in file order with dynamic shapes (shapes are whatever the tensors carry at run time).
// An operator without an implementation, or one that fails on the shapes it receives,
// raises isegman::Error naming the model file and the node.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "models/onnx_model.h"

namespace isegman::models {

// Sets libtorch's intra-op thread count once per process (later calls do nothing) and
// tunes malloc to reuse freed tensor memory. threads = 0: all cores when the process was
// started with OMP_WAIT_POLICY=PASSIVE, else 1 (spinning OpenMP workers make 2 threads much
// slower than 1 on small VMs; the policy cannot be changed once the process runs).
void configure_threads(int threads = 0);
// Limits the intra-op threads of graphs run from the calling thread only (OpenMP keeps
// the thread count per thread): lets a caller run several small graphs side by side,
// one core each, while the process default stays as configured.
void limit_threads_of_this_thread(int threads);
int threads_of_this_thread();

class OnnxGraph {
 public:
  // What run() returns, chosen by a rule over the loaded model (optional):
  // `taps` names values computed inside the graph, returned beside the graph outputs
  // (appended to outputs()): e.g. a decoder's scores before the graph keeps only the best.
  // A name no node produces is an error. `unread` names graph outputs the caller never
  // reads: they stay in outputs() but are not returned, and nodes that only they need
  // are not run.
  struct OutputChoice {
    std::vector<std::string> taps, unread;
  };
  using OutputRule = std::function<OutputChoice(const OnnxModel&)>;
  explicit OnnxGraph(const std::string& path, const OutputRule& rule = nullptr);
  ~OnnxGraph();
  OnnxGraph(const OnnxGraph&) = delete;
  OnnxGraph& operator=(const OnnxGraph&) = delete;

  const std::string& path() const;
  const std::vector<ValueInfo>& inputs() const;
  const std::vector<ValueInfo>& outputs() const;
  // Operator types the graph uses after constant folding, sorted, unique.
  std::vector<std::string> op_types() const;
  size_t node_count() const;  // nodes left after folding

  // Runs the graph. `feeds` must hold every graph input; returns every graph output but
  // the unread ones, and the taps.
  std::map<std::string, HostTensor> run(const std::map<std::string, HostTensor>& feeds) const;

  // Every operator type the executor implements (default ONNX domain).
  static std::vector<std::string> supported_ops();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace isegman::models
