#pragma once
// Suggestions for misspelt names (keys, nodes, components): the optimal-string-alignment
// (Damerau–Levenshtein) distance and the nearest plausible candidate.

#include <algorithm>
#include <string>
#include <vector>

namespace shudder {

/// Optimal-string-alignment (Damerau–Levenshtein) distance: insertions, deletions,
/// substitutions and swaps of adjacent characters, each costing 1.
inline std::size_t edit_distance(const std::string& a, const std::string& b) {
  // d[i][j]: distance between a's first i and b's first j characters (Wagner–Fischer with the
  // adjacent-swap case of Damerau).
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

/// The candidate nearest to `key` if it is a plausible misspelling: distance <= 2 and at most a
/// third of `key`'s length (so "fluid" does not suggest "lining"); ties go to the first
/// candidate. "" when none is that near.
inline std::string nearest_key(const std::string& key, const std::vector<std::string>& candidates) {
  const std::size_t limit = std::min<std::size_t>(2, key.size() / 3);
  std::string best;
  std::size_t best_d = limit + 1;
  for (const auto& c : candidates) {
    const std::size_t dist = edit_distance(key, c);
    if (dist < best_d) {
      best_d = dist;
      best = c;
    }
  }
  return best;
}

}  // namespace shudder
