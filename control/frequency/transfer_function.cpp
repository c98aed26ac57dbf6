#include "control/frequency/transfer_function.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace netmc::control {
namespace {

// Messages built by appending: GCC 12 at -O3 reports a false -Wrestrict on literal + const char*.
[[noreturn]] void fail(const char* which, const char* problem) {
  std::string message = "transfer function: the ";
  message += which;
  message += problem;
  throw std::invalid_argument(message);
}

void require_finite(const std::vector<double>& coefficients, const char* which) {
  if (coefficients.empty()) fail(which, " has no coefficients");
  for (const double c : coefficients) {
    if (!std::isfinite(c)) fail(which, " has a non-finite coefficient");
  }
}

// Sum of two polynomials of possibly different degree, aligned at the constant term.
std::vector<double> polynomial_sum(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> sum(std::max(a.size(), b.size()), 0.0);
  std::copy(a.begin(), a.end(), sum.end() - static_cast<std::ptrdiff_t>(a.size()));
  for (std::size_t i = 0; i < b.size(); ++i) sum[sum.size() - b.size() + i] += b[i];
  return sum;
}

std::string polynomial_text(const std::vector<double>& p) {
  std::ostringstream text;
  text.precision(6);
  bool first = true;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double c = p[i];
    if (c == 0.0 && !(first && i + 1 == p.size())) continue;
    const std::size_t power = p.size() - 1 - i;
    if (first) {
      if (c < 0.0) text << "-";
    } else {
      text << (c < 0.0 ? " - " : " + ");
    }
    const double magnitude = std::abs(c);
    if (magnitude != 1.0 || power == 0) text << magnitude << (power > 0 ? " " : "");
    if (power == 1) text << "s";
    if (power > 1) text << "s^" << power;
    first = false;
  }
  return text.str();
}

}  // namespace

TransferFunction::TransferFunction(std::vector<double> numerator, std::vector<double> denominator)
    : numerator_(std::move(numerator)), denominator_(std::move(denominator)) {
  require_finite(numerator_, "numerator");
  require_finite(denominator_, "denominator");
  if (denominator_.front() == 0.0) {
    throw std::invalid_argument("transfer function: the denominator's leading coefficient is zero");
  }
  const auto first_nonzero = std::find_if(numerator_.begin(), numerator_.end(), [](double c) { return c != 0.0; });
  if (first_nonzero == numerator_.end()) {
    numerator_ = {0.0};
  } else {
    numerator_.erase(numerator_.begin(), first_nonzero);
  }
}

TransferFunction TransferFunction::gain(double k) { return {{k}, {1.0}}; }

TransferFunction TransferFunction::integrator() { return {{1.0}, {1.0, 0.0}}; }

std::complex<double> TransferFunction::evaluate(std::complex<double> s) const {
  const auto horner = [s](const std::vector<double>& p) {
    std::complex<double> value = 0.0;
    for (const double c : p) value = value * s + c;
    return value;
  };
  return horner(numerator_) / horner(denominator_);
}

std::string TransferFunction::describe() const {
  const bool unit_denominator = denominator_.size() == 1 && denominator_.front() == 1.0;
  if (unit_denominator) return polynomial_text(numerator_);
  // Parentheses only around sums: "2.2e+09 / s", "(s + 1) / (s^2 + 2 s + 1)".
  const auto factor = [](std::ostringstream& text, const std::vector<double>& p) {
    const bool sum = std::count_if(p.begin(), p.end(), [](double c) { return c != 0.0; }) > 1;
    if (sum) text << "(";
    text << polynomial_text(p);
    if (sum) text << ")";
  };
  std::ostringstream text;
  factor(text, numerator_);
  text << " / ";
  factor(text, denominator_);
  return text.str();
}

std::vector<double> polynomial_product(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> product(a.size() + b.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) product[i + j] += a[i] * b[j];
  }
  return product;
}

TransferFunction operator*(const TransferFunction& a, const TransferFunction& b) {
  return {polynomial_product(a.numerator(), b.numerator()), polynomial_product(a.denominator(), b.denominator())};
}

TransferFunction operator+(const TransferFunction& a, const TransferFunction& b) {
  return {polynomial_sum(polynomial_product(a.numerator(), b.denominator()),
                         polynomial_product(b.numerator(), a.denominator())),
          polynomial_product(a.denominator(), b.denominator())};
}

TransferFunction feedback(const TransferFunction& forward, const TransferFunction& back) {
  // G/(1 + GH) = N_G D_H / (D_G D_H + N_G N_H)
  std::vector<double> denominator = polynomial_sum(polynomial_product(forward.denominator(), back.denominator()),
                                                   polynomial_product(forward.numerator(), back.numerator()));
  const auto first_nonzero = std::find_if(denominator.begin(), denominator.end(), [](double c) { return c != 0.0; });
  if (first_nonzero == denominator.end()) {
    throw std::invalid_argument("feedback: 1 + G H is identically zero (an ill-posed loop)");
  }
  denominator.erase(denominator.begin(), first_nonzero);
  return {polynomial_product(forward.numerator(), back.denominator()), std::move(denominator)};
}

}  // namespace netmc::control
