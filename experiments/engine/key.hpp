// A number that keys a container or orders a list: exact and totally ordered.
//
// A double is not a key. NaN compares false with everything, so a std::map or std::set keyed by
// doubles treats a NaN as equal to whatever it meets and overwrites or drops an entry, and a sort
// whose comparator sees a NaN is undefined. Every map, set and sort of numbers in the reports
// goes through Key (or key_less): a Key holds a finite value, refused where it is made with a
// message naming what it keys, and orders by value, with -0 and +0 one key.
#pragma once

#include <cmath>
#include <compare>
#include <limits>
#include <stdexcept>
#include <string>

namespace mpmstab {

class Key {
 public:
  // `what` names the value in the refusal ("Table 1's dt", "E").
  explicit Key(double v, const char* what = "a key") : v_(v + 0.0) {
    if (!std::isfinite(v))
      throw std::invalid_argument(std::string(what) + ": not a finite number, cannot key a result");
  }
  double value() const { return v_; }
  operator double() const { return v_; }  // a Key reads as its value

  friend std::strong_ordering operator<=>(Key a, Key b) {
    // Finite values, -0 folded into +0: < and == are a total order here.
    return a.v_ < b.v_
               ? std::strong_ordering::less
               : (b.v_ < a.v_ ? std::strong_ordering::greater : std::strong_ordering::equal);
  }
  friend bool operator==(Key a, Key b) { return a.v_ == b.v_; }

 private:
  double v_;
};

// The comparator of a sort of numbers that may hold a NaN: IEEE 754's total order, with -0 and
// +0 one value and every NaN one value after +inf, so that the sort is defined and the NaN is in
// plain sight at the end. (totalOrder alone puts a NaN with its sign bit set before -inf, and
// 0/0 on x86 is such a NaN.)
struct TotalLess {
  bool operator()(double a, double b) const {
    return std::strong_order(canonical(a), canonical(b)) < 0;
  }

 private:
  static double canonical(double x) {
    return std::isnan(x) ? std::numeric_limits<double>::quiet_NaN() : x + 0.0;
  }
};

}  // namespace mpmstab
