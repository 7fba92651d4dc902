#pragma once
// FFTW wisdom shipped as code, so that a short `shudder run` does not pay FFTW's planner.
//
// Why: FftPlan plans with FFTW_ESTIMATE (no timing runs), yet FFTW's estimate still searches
// its solvers recursively: the 512- and 256-point plans of one Paper G Case 1 verdict cost
// 8.5 M instructions, a tenth of the whole process (docs/performance.md). Wisdom records the
// planner's choice for each (sub)problem; with it imported the planner only re-creates that
// choice. The shipped text was made by the same planner with the same flags
// (FFTW_ESTIMATE | FFTW_UNALIGNED), so a plan made from it is the plan the estimate picks here:
// transforms are bit-identical (tests/analysis/test_fftw_wisdom.cpp).
//
// Safety: FFTW checks the text's header (its version and the hash of its solver set) and
// refuses wisdom from another FFTW build as a whole; a solver the wisdom names that is not
// usable on this CPU makes FFTW discard the wisdom and plan afresh ("bogus wisdom"). Either way
// the planner then plans exactly as without wisdom, only slower.
//
// Which lengths: the detector's Welch and spectrogram segments are powers of two (16 … 65536
// covers every record up to 10^5 s at 10 kHz); amplitude spectra of other lengths are planned
// as before. Regenerate after an FFTW upgrade: ./build/bench/shudder_fftw_wisdom >
// analysis/fftw_wisdom_data.cpp (its output is that file).

#include <cstddef>
#include <span>
#include <string>

namespace shudder::analysis {

/// FFTW's wisdom text for kShippedFftwLengths (analysis/fftw_wisdom_data.cpp).
extern const char* const kShippedFftwWisdom;

/// The r2c transform lengths the shipped wisdom was made for: 2^4 … 2^16.
inline constexpr std::size_t kShippedFftwLengths[] = {16,   32,   64,   128,   256,   512,  1024,
                                                      2048, 4096, 8192, 16384, 32768, 65536};

/// FFTW's wisdom text after planning each length as FftPlan does, starting from no wisdom
/// (it forgets the process' wisdom first; plans made afterwards plan afresh). For the generator
/// bench/fftw_wisdom.cpp and the tests.
std::string fftw_wisdom_for_lengths(std::span<const std::size_t> lengths);

/// Whether the shipped wisdom was accepted by this process' FFTW (false before the first
/// FftPlan, or after fftw_wisdom_for_lengths made the process forget it).
bool shipped_fftw_wisdom_in_use();

}  // namespace shudder::analysis
