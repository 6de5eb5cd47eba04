#include "dispersion/real_fft.hpp"

#include <fftw3.h>

#include <mutex>
#include <new>

namespace shpb {
namespace {
// FFTW's planner is not thread-safe (only fftw_execute is): plans are made and destroyed under
// one lock, so that threads (the fit's parallel simulations) can each own a RealFft.
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}
}  // namespace

RealFft::RealFft(std::size_t n) : n_(n) {
  real_ = static_cast<double*>(fftw_malloc(sizeof(double) * n));
  spectrum_ = static_cast<std::complex<double>*>(fftw_malloc(sizeof(fftw_complex) * (n / 2 + 1)));
  if (!real_ || !spectrum_) {
    fftw_free(real_);
    fftw_free(spectrum_);
    throw std::bad_alloc();
  }
  auto* c = reinterpret_cast<fftw_complex*>(spectrum_);
  const int len = static_cast<int>(n);
  const std::lock_guard lock(planner_mutex());
  // FFTW_ESTIMATE: planning must not overwrite data nor take seconds for one-off records.
  forward_plan_ = fftw_plan_dft_r2c_1d(len, real_, c, FFTW_ESTIMATE);
  inverse_plan_ = fftw_plan_dft_c2r_1d(len, c, real_, FFTW_ESTIMATE);
}

RealFft::~RealFft() {
  const std::lock_guard lock(planner_mutex());
  if (forward_plan_) fftw_destroy_plan(static_cast<fftw_plan>(forward_plan_));
  if (inverse_plan_) fftw_destroy_plan(static_cast<fftw_plan>(inverse_plan_));
  fftw_free(real_);
  fftw_free(spectrum_);
}

void RealFft::forward() { fftw_execute(static_cast<fftw_plan>(forward_plan_)); }

void RealFft::inverse() {
  fftw_execute(static_cast<fftw_plan>(inverse_plan_));
  const double scale = 1.0 / static_cast<double>(n_);
  for (std::size_t i = 0; i < n_; ++i) real_[i] *= scale;
}

RealFft& FftPlans::of_size(std::size_t n) {
  for (const auto& f : ffts_)
    if (f->size() == n) return *f;
  return *ffts_.emplace_back(std::make_unique<RealFft>(n));
}

std::size_t fast_fft_size(std::size_t n) {
  for (std::size_t m = n < 1 ? 1 : n;; ++m) {
    std::size_t r = m;
    for (std::size_t p : {2, 3, 5, 7})
      while (r % p == 0) r /= p;
    if (r == 1) return m;
  }
}

}  // namespace shpb
