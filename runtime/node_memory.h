#pragma once
// Memory for a table's node data, on huge pages where the system grants them (Linux, with
// transparent huge pages "always" or "madvise"): a random lookup reads 16–32 rows spread over
// tens of megabytes, and with 4 KiB pages each row is also a TLB miss, a page walk added to its
// cache miss. Zero-initialised numbers (double, or float for float32 storage); elsewhere than
// Linux an ordinary allocation.

#include <cstddef>

namespace wrc::runtime {

template <typename T>
class NodeMemory {
 public:
  NodeMemory() = default;
  /// `count` zeros. Throws std::bad_alloc when the memory cannot be had.
  explicit NodeMemory(std::size_t count);
  ~NodeMemory();
  NodeMemory(NodeMemory&& other) noexcept;
  NodeMemory& operator=(NodeMemory&& other) noexcept;
  NodeMemory(const NodeMemory& other);
  NodeMemory& operator=(const NodeMemory& other);

  T* data() noexcept { return data_; }
  const T* data() const noexcept { return data_; }
  std::size_t size() const noexcept { return size_; }
  bool empty() const noexcept { return size_ == 0; }
  T& operator[](std::size_t i) noexcept { return data_[i]; }
  const T& operator[](std::size_t i) const noexcept { return data_[i]; }

 private:
  void Release() noexcept;

  T* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t bytes_ = 0;  // as mapped
};

extern template class NodeMemory<double>;
extern template class NodeMemory<float>;

}  // namespace wrc::runtime
