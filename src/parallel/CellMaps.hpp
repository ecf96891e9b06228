#pragma once
#include <string>
#include <utility>
#include <vector>

#include "core/CellGrid.hpp"

namespace rondel {

// The cell-to-rank maps of the grid and metis partitioners (PartitionGrid.cpp, PartitionMetis.cpp) as plain
// functions, tested on their own (tests/parallel/test_partitioners.cpp). Each is a deterministic function of its
// inputs, so every rank computes (or receives) the same map.
//  - grid: regular px x py blocks of cells (px py = ranks, blocks as square as the grid allows); no METIS.
//  - metis: k-way partition of the cell graph (8-neighbour stencil, periodic wrap) with vertex weights
//    (the work per cell: discs + contacts, plus one), fixed seed; the new parts are relabelled so that
//    most of the weight stays on the rank that had it.
std::vector<int> grid_partition(const CellGrid& grid, int ranks);
// The grid partitioner's px x py blocks, and the block (rank) of cell (cx, cy): the map without a table.
std::pair<int, int> grid_blocks(const CellGrid& grid, int ranks);
int grid_block_of(const CellGrid& grid, std::pair<int, int> blocks, int cx, int cy);
std::vector<int> metis_partition(const CellGrid& grid, int ranks, const std::vector<long>& weights,
                                 const std::vector<int>& previous);
// Relabels `parts` (values 0..ranks-1) to maximise the weight that keeps its previous rank (greedy on the
// overlap, ties broken by the lower index).
std::vector<int> relabel_parts(const std::vector<int>& parts, const std::vector<int>& previous,
                               const std::vector<long>& weights, int ranks);

}  // namespace rondel
