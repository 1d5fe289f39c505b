#include "roadbrdf/core/nearest_name.h"

#include <algorithm>
#include <limits>

namespace roadbrdf {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  const std::size_t n = a.size(), m = b.size();
  // Three rows of the dynamic-programming table: i - 2, i - 1 and i.
  std::vector<std::size_t> before(m + 1), previous(m + 1), current(m + 1);
  for (std::size_t j = 0; j <= m; ++j) previous[j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        current[j] = std::min(current[j], before[j - 2] + 1);
      }
    }
    before.swap(previous);
    previous.swap(current);
  }
  return previous[m];
}

namespace {
std::string_view without_dashes(std::string_view s) {
  while (!s.empty() && s.front() == '-') s.remove_prefix(1);
  return s;
}
}  // namespace

std::string nearest_name(std::string_view word, const std::vector<std::string>& candidates) {
  const std::string_view w = without_dashes(word);
  if (w.empty()) return "";
  const std::size_t limit = std::max<std::size_t>(1, w.size() / 3);
  std::size_t best = std::numeric_limits<std::size_t>::max();
  std::string answer;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(w, without_dashes(c));
    if (d < best) {
      best = d;
      answer = c;
    }
  }
  if (best <= limit) return answer;
  std::string prefix_match;
  for (const auto& c : candidates) {
    if (without_dashes(c).substr(0, w.size()) == w) {
      if (!prefix_match.empty()) return "";  // ambiguous
      prefix_match = c;
    }
  }
  return prefix_match;
}

std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates) {
  const std::string near = nearest_name(word, candidates);
  return near.empty() ? std::string() : " (did you mean '" + near + "'?)";
}

}  // namespace roadbrdf
