// The shape-function values of one step, kept from p2g for g2p and the stress update.
//
// All three phases use S_ip and G_ip at the particle positions x^n of the start of the step, so
// they are evaluated once (in p2g) and kept here. The values are stored as a struct of arrays,
// one array per stencil slot k (node base + k), so that the loops over particles vectorize.
#pragma once

#include <array>
#include <cstddef>
#include <new>
#include <vector>

namespace mpmstab {

// Storage aligned to a cache line (64 bytes), so that p2g's vector stores of 8 values never
// straddle two lines.
template <class T>
struct CacheLineAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlign{64};
  CacheLineAllocator() = default;
  template <class U>
  CacheLineAllocator(const CacheLineAllocator<U>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlign)); }
  void deallocate(T* p, std::size_t) { ::operator delete(p, kAlign); }
  friend bool operator==(const CacheLineAllocator&, const CacheLineAllocator&) { return true; }
};
template <class T>
using AlignedVector = std::vector<T, CacheLineAllocator<T>>;

template <int W>
struct Stencil {
  static constexpr int width = W;
  AlignedVector<int> base;                 // storage index (Grid) of the first node touched
  std::array<AlignedVector<double>, W> w;  // w[k][p] = S_ip for node base[p] + k
  std::array<AlignedVector<double>, W> g;  // g[k][p] = G_ip for node base[p] + k

  void resize(std::size_t n) {
    base.resize(n);
    for (int k = 0; k < W; ++k)
      for (auto* a : {&w[k], &g[k]})
        a->resize(n);
  }
  std::size_t size() const { return base.size(); }
};

}  // namespace mpmstab
