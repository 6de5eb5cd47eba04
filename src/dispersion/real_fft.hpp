#pragma once
// FFTW real-to-complex / complex-to-real transforms of one length with their buffers, planned
// once (RAII). Reuse one RealFft for every record of the same length; never plan in a loop.
#include <complex>
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace shpb {

class RealFft {
 public:
  explicit RealFft(std::size_t n);
  ~RealFft();
  RealFft(const RealFft&) = delete;
  RealFft& operator=(const RealFft&) = delete;

  std::size_t size() const { return n_; }
  std::span<double> samples() { return {real_, n_}; }                             // n values
  std::span<std::complex<double>> spectrum() { return {spectrum_, n_ / 2 + 1}; }  // n/2+1 bins

  void forward();  // samples → spectrum (unnormalised)
  void inverse();  // spectrum → samples, divided by n so forward+inverse is the identity

 private:
  std::size_t n_;
  double* real_ = nullptr;
  std::complex<double>* spectrum_ = nullptr;
  void* forward_plan_ = nullptr;
  void* inverse_plan_ = nullptr;
};

// The transforms of every length asked for, each planned once: the corrections of one record
// (3–6 of them, of one or two padded lengths) share it instead of planning their own.
class FftPlans {
 public:
  RealFft& of_size(std::size_t n);

 private:
  std::vector<std::unique_ptr<RealFft>> ffts_;
};

// Smallest n' ≥ n of the form 2^a 3^b 5^c 7^d (fast FFTW lengths).
std::size_t fast_fft_size(std::size_t n);

}  // namespace shpb
