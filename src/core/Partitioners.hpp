#pragma once
// The partitioners' registry (docs/developing.md, "How to add a partitioner"): one tag per word of
// parallel.partitioner, listed once in `Partitioners`. parallel/ implements each tag in its own file
// (PartitionSfc.cpp, ...) with a make_partition overload declared in parallel/Partition.hpp: the dispatch there
// instantiates the overload of every tag of the list, so a tag without one does not build, and nothing else names
// a partitioner. The configuration reads the key against the list and --help prints it; the memory check takes the
// bytes per cell from the tag.
#include <span>
#include <string>
#include <vector>

#include "core/KeyTable.hpp"
#include "core/MemoryLimit.hpp"

namespace rondel {

// sfc: the cells in Hilbert-curve order cut into P contiguous key ranges of equal work (docs/design.md section 6).
struct SfcPartitioner {
  static constexpr const char* name = "sfc";
  static constexpr const char* help = "Hilbert-curve cuts, the default";
  static constexpr double bytes_per_cell = kBytesPerCell;
};
// grid: px x py regular blocks of cells, the owner computed (no table).
struct GridPartitioner {
  static constexpr const char* name = "grid";
  static constexpr const char* help = "blocks";
  static constexpr double bytes_per_cell = kBytesPerCell;
};
// metis: a k-way METIS partition of the whole cell graph, computed on rank 0 and broadcast.
struct MetisPartitioner {
  static constexpr const char* name = "metis";
  static constexpr const char* help = "graph partition; every rank holds the whole cell map: moderate sizes";
  static constexpr double bytes_per_cell = kBytesPerMetisCell;
};

template <class... Tags>
struct PartitionerList {
  // Calls f.template operator()<Tag>() for the tag named `name`; false when none is.
  template <class F>
  static bool with(const std::string& name, F&& f) {
    return ((name == Tags::name ? (f.template operator()<Tags>(), true) : false) || ...);
  }
  // The words of parallel.partitioner (the first is its default).
  static std::span<const config::Choice<std::string>> choices() {
    static const std::vector<config::Choice<std::string>> list{{Tags::name, Tags::name, Tags::help}...};
    return list;
  }
  static double bytes_per_cell(const std::string& name) {
    double bytes = 0.0;
    with(name, [&bytes]<class Tag>() { bytes = Tag::bytes_per_cell; });
    return bytes;
  }
};

// The registry rows; the first is the default.
using Partitioners = PartitionerList<SfcPartitioner, GridPartitioner, MetisPartitioner>;

}  // namespace rondel
