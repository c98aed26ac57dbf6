#pragma once
// A continuous-time rational transfer function N(s)/D(s) with real coefficients, highest power
// first (as MATLAB's tf): enough algebra to build the loops of a frequency-domain design and to
// evaluate them on the jω axis.

#include <complex>
#include <string>
#include <vector>

namespace netmc::control {

class TransferFunction {
 public:
  // Throws std::invalid_argument for an empty polynomial, a non-finite coefficient or a zero
  // leading denominator coefficient. Leading zeros of the numerator are dropped (a sum can
  // cancel its highest terms); an all-zero numerator is the zero function.
  TransferFunction(std::vector<double> numerator, std::vector<double> denominator);

  static TransferFunction gain(double k);
  static TransferFunction integrator();  // 1/s

  const std::vector<double>& numerator() const { return numerator_; }
  const std::vector<double>& denominator() const { return denominator_; }
  bool is_proper() const { return numerator_.size() <= denominator_.size(); }

  // G(s) at a complex s (Horner).
  std::complex<double> evaluate(std::complex<double> s) const;
  // The frequency response G(jω).
  std::complex<double> at(double omega_rad_s) const { return evaluate({0.0, omega_rad_s}); }

  // "(2 s + 1) / (s^2 + 3 s + 2)"
  std::string describe() const;

 private:
  std::vector<double> numerator_;
  std::vector<double> denominator_;
};

TransferFunction operator*(const TransferFunction& a, const TransferFunction& b);  // series
TransferFunction operator+(const TransferFunction& a, const TransferFunction& b);  // parallel
// Negative feedback G/(1 + G H); throws std::invalid_argument when 1 + G H is identically zero
// (an ill-posed loop such as G = -1, H = 1).
TransferFunction feedback(const TransferFunction& forward, const TransferFunction& back);

// Coefficients of the product of two polynomials (highest power first).
std::vector<double> polynomial_product(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace netmc::control
