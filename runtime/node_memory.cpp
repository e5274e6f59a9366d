#include "runtime/node_memory.h"

#include <algorithm>
#include <new>
#include <utility>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace wrc::runtime {
namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;

}  // namespace

template <typename T>
NodeMemory<T>::NodeMemory(std::size_t count) : size_(count) {
  if (count == 0) return;
#if defined(__linux__)
  // Anonymous pages are zero; a whole number of huge pages, so that the last one can be huge too.
  bytes_ = (count * sizeof(T) + kHugePage - 1) / kHugePage * kHugePage;
  void* p = mmap(nullptr, bytes_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) throw std::bad_alloc();
  madvise(p, bytes_, MADV_HUGEPAGE);  // advice: without huge pages the table works as before
  data_ = static_cast<T*>(p);
#else
  data_ = new T[count]();
#endif
}

template <typename T>
void NodeMemory<T>::Release() noexcept {
  if (data_ == nullptr) return;
#if defined(__linux__)
  munmap(data_, bytes_);
#else
  delete[] data_;
#endif
  data_ = nullptr;
  size_ = bytes_ = 0;
}

template <typename T>
NodeMemory<T>::~NodeMemory() {
  Release();
}

template <typename T>
NodeMemory<T>::NodeMemory(NodeMemory&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)),
      size_(std::exchange(other.size_, 0)),
      bytes_(std::exchange(other.bytes_, 0)) {}

template <typename T>
NodeMemory<T>& NodeMemory<T>::operator=(NodeMemory&& other) noexcept {
  if (this != &other) {
    Release();
    data_ = std::exchange(other.data_, nullptr);
    size_ = std::exchange(other.size_, 0);
    bytes_ = std::exchange(other.bytes_, 0);
  }
  return *this;
}

template <typename T>
NodeMemory<T>::NodeMemory(const NodeMemory& other) : NodeMemory(other.size_) {
  std::copy(other.data_, other.data_ + other.size_, data_);
}

template <typename T>
NodeMemory<T>& NodeMemory<T>::operator=(const NodeMemory& other) {
  if (this != &other) *this = NodeMemory(other);
  return *this;
}

template class NodeMemory<double>;
template class NodeMemory<float>;

}  // namespace wrc::runtime
