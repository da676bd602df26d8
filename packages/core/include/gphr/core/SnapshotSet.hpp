#pragma once
/// @file
/// The training snapshots of the offline stages: one block of states (a MultiVector, a column per
/// state) per training parameter, either held in memory or streamed, each block read when a stage
/// asks for it and released when the stage moves on. A stage may also read a block's states in
/// column blocks (columns()): streamed, it then holds one column block at a time, however many
/// parameters were trained and however long each trajectory is: the basis, the DEIM basis, the
/// term-weight fits and the gradient-DEIM baseline read the snapshots this way.
#include <algorithm>
#include <functional>
#include <initializer_list>
#include <utility>
#include <vector>

#include "gphr/core/Types.hpp"

namespace gphr {

/// States per read of the stages that read a block in column blocks (SnapshotSet::columns) without
/// a POD step size of their own: what one read holds, whatever a trajectory's length.
constexpr size_t kSnapshotReadColumns = 64;

/// The snapshot blocks of the training parameters (see the file's description).
class SnapshotSet {
 public:
  /// Reads `count` of block j's states first every, (first + 1) every, ... (count kAll: all from
  /// first on; collective over the blocks' communicator when it reads a file).
  using Loader = std::function<RCP<const MultiVector>(size_t j, size_t every, size_t first, size_t count)>;
  static constexpr size_t kAll = static_cast<size_t>(-1);  ///< Loader's count: every state from `first` on.
  SnapshotSet() = default;
  /// Blocks held in memory (implicit: every stage also takes a plain vector of blocks).
  SnapshotSet(std::vector<RCP<const MultiVector>> blocks) : blocks_(std::move(blocks)) {  // NOLINT
    for (const auto& b : blocks_) columns_.push_back(b->getNumVectors());
  }
  /// Blocks held in memory, listed: {Y1, Y2, ...}.
  SnapshotSet(std::initializer_list<RCP<const MultiVector>> blocks)
      : SnapshotSet(std::vector<RCP<const MultiVector>>(blocks)) {}
  /// Streamed blocks: columns[j] states in block j, read by load(j, ...) on each access.
  SnapshotSet(std::vector<size_t> columns, Loader load) : columns_(std::move(columns)), load_(std::move(load)) {}
  size_t size() const { return columns_.size(); }  ///< The number of blocks (training parameters).
  bool empty() const { return columns_.empty(); }  ///< Whether there is no block.
  bool streamed() const { return static_cast<bool>(load_); }  ///< Whether blocks are read on access.
  /// The number of states in block j, without reading it.
  size_t numColumns(size_t j) const { return columns_.at(j); }
  /// Block j: held, or read now (a streamed block lives as long as the caller keeps it).
  RCP<const MultiVector> operator[](size_t j) const { return load_ ? load_(j, 1, 0, kAll) : blocks_.at(j); }
  /// Block j's states 0, every, 2 every, ... (ceil(numColumns(j) / every) columns): a view of a
  /// held block, or only those states read (a stage that uses every N-th state reads 1/N of them).
  RCP<const MultiVector> everyNth(size_t j, size_t every) const;
  /// `count` of those states from the `first`-th on (states first every, (first + 1) every, ...):
  /// a view of a held block, or only those states read. first + count <= ceil(numColumns(j) / every).
  RCP<const MultiVector> columns(size_t j, size_t every, size_t first, size_t count) const;

  /// Visits the blocks in order, each read once (streamed: one in memory at a time).
  class Iterator {
   public:
    Iterator(const SnapshotSet* set, size_t j) : set_(set), j_(j) {}  ///< At block j of `set`.
    RCP<const MultiVector> operator*() const { return (*set_)[j_]; }  ///< The block (read now).
    Iterator& operator++() {  ///< The next block.
      ++j_;
      return *this;
    }
    bool operator!=(const Iterator& o) const { return j_ != o.j_; }  ///< For range-for.

   private:
    const SnapshotSet* set_;
    size_t j_;
  };
  Iterator begin() const { return Iterator(this, 0); }       ///< The first block.
  Iterator end() const { return Iterator(this, size()); }    ///< Past the last block.

 private:
  std::vector<size_t> columns_;
  std::vector<RCP<const MultiVector>> blocks_;
  Loader load_;
};

inline RCP<const MultiVector> SnapshotSet::everyNth(size_t j, size_t every) const {
  if (every <= 1) return (*this)[j];
  if (load_) return load_(j, every, 0, kAll);
  std::vector<size_t> cols;
  for (size_t c = 0; c < columns_.at(j); c += every) cols.push_back(c);
  return blocks_[j]->subView(Teuchos::ArrayView<const size_t>(cols));
}

inline RCP<const MultiVector> SnapshotSet::columns(size_t j, size_t every, size_t first, size_t count) const {
  every = std::max<size_t>(every, 1);
  if (load_) return load_(j, every, first, count);
  if (every == 1 && count > 0)  // a contiguous view (constant stride: its local view indexes as a block)
    return blocks_.at(j)->subView(Teuchos::Range1D(first, std::min(first + count, columns_.at(j)) - 1));
  std::vector<size_t> cols;
  for (size_t u = first; u < first + count && u * every < columns_.at(j); ++u) cols.push_back(u * every);
  return blocks_.at(j)->subView(Teuchos::ArrayView<const size_t>(cols));
}

}  // namespace gphr
