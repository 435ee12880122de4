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

  // The values a run computes from some of its inputs alone (the "stable" ones) and the
  // shapes of the others, kept for later runs that give the same stable inputs: a SAM
  // decoder's projections of the image embedding are the same for every click on that
  // image. Immutable once made; shared freely between threads.
  struct Stable;
  // Runs the graph as run(feeds) does and also keeps, in `stable`, the values of the nodes
  // whose runtime inputs all derive from the inputs named in `stable_inputs`, or from shapes
  // of the other inputs (the shape arithmetic an export makes to broadcast or tile).
  std::map<std::string, HostTensor> run(const std::map<std::string, HostTensor>& feeds,
                                        const std::vector<std::string>& stable_inputs,
                                        std::shared_ptr<const Stable>& stable) const;
  // Runs the rest: `feeds` must hold every graph input but the stable ones. Returns what
  // run() returns for both feeds together, bit for bit; when the shape arithmetic gives
  // other values than when `stable` was made, the whole graph runs instead.
  std::map<std::string, HostTensor> run(const std::map<std::string, HostTensor>& feeds, const Stable& stable) const;
  // Bytes the kept values of `stable` hold beyond the stable inputs themselves.
  static size_t stable_bytes(const Stable& stable);
  // How many runs from `stable` found other shape values and ran the whole graph.
  static size_t whole_runs(const Stable& stable);
  // This graph's identity, unique in the process (kept values name the graph they belong to).
  uint64_t id() const;

  // Every operator type the executor implements (default ONNX domain).
  static std::vector<std::string> supported_ops();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace isegman::models
