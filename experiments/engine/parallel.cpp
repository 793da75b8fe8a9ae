#include "parallel.hpp"

#include <atomic>
#include <exception>
#include <thread>
#include <vector>

namespace mpmstab {

void for_each_in_parallel(std::size_t n, unsigned threads,
                          const std::function<void(std::size_t)>& work) {
  std::vector<std::exception_ptr> errors(n);
  std::atomic<std::size_t> next{0};
  const auto take = [&] {
    for (std::size_t i = next++; i < n; i = next++) {
      try {
        work(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads && t < n; ++t)
    pool.emplace_back(take);
  take();
  for (auto& t : pool)
    t.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace mpmstab
