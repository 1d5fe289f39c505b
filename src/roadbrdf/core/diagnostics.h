// What a task has to say besides its value: notes (information) and warnings (the result may be
// wrong or misleading). Each is structured, a kind and a message, so that a front end never sorts
// them by the text of the message: the command line prints "roadbrdf: note: MESSAGE" and
// "roadbrdf: warning: MESSAGE", Python issues warnings, and the JSON result lists them.
//
// The library never writes to standard error: a reader or a computation that has something to say
// adds it to the Diagnostics of its result, or passes it to the DiagnosticSink of its request.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace roadbrdf {

struct Diagnostic {
  // A short stable identifier of what happened ("extrapolated", "flux_mismatch", "no_upward_brdf"):
  // for programs that react to it. Lower case, words joined by '_'.
  std::string kind;
  // One sentence for the user. It may name request fields between backquotes (`field`,
  // core/error.h field_reference), which each front end spells its own way.
  std::string message;

  friend bool operator==(const Diagnostic&, const Diagnostic&) = default;
};

enum class Severity { note, warning };

struct Diagnostics {
  std::vector<Diagnostic> notes;
  std::vector<Diagnostic> warnings;

  void note(std::string kind, std::string message) { notes.push_back({std::move(kind), std::move(message)}); }
  void warn(std::string kind, std::string message) { warnings.push_back({std::move(kind), std::move(message)}); }
  void append(const Diagnostics& other) {
    notes.insert(notes.end(), other.notes.begin(), other.notes.end());
    warnings.insert(warnings.end(), other.warnings.begin(), other.warnings.end());
  }
  bool has_warning(const std::string& kind) const {
    for (const Diagnostic& w : warnings) {
      if (w.kind == kind) return true;
    }
    return false;
  }
  // {"notes": [{"kind": ..., "message": ...}, ...], "warnings": [...]}: the members every JSON
  // result carries.
  nlohmann::json to_json() const {
    const auto list = [](const std::vector<Diagnostic>& items) {
      nlohmann::json out = nlohmann::json::array();
      for (const Diagnostic& d : items) out.push_back({{"kind", d.kind}, {"message", d.message}});
      return out;
    };
    return {{"notes", list(notes)}, {"warnings", list(warnings)}};
  }
};

// Where a reader called deep inside a task sends what it has to say (see above).
using DiagnosticSink = std::function<void(Severity, const Diagnostic&)>;

// The front end's sink for warnings of readers whose caller passed none (a reader's `warn` option left
// empty): the command line installs one that prints "roadbrdf: warning: MESSAGE" on standard error,
// Python one that issues roadbrdf.RoadbrdfWarning. Until one is installed (a C++ program using the
// library directly) such warnings are kept, in order, for take_unrouted_warnings(): the library itself
// never prints. Thread-safe.
void set_front_end_warning_sink(std::function<void(const std::string&)> sink);
void route_warning(const std::string& message);
std::vector<std::string> take_unrouted_warnings();

// A sink that collects into `diagnostics` (which must outlive it).
inline DiagnosticSink collect_into(Diagnostics& diagnostics) {
  return [&diagnostics](Severity severity, const Diagnostic& d) {
    (severity == Severity::note ? diagnostics.notes : diagnostics.warnings).push_back(d);
  };
}

}  // namespace roadbrdf
