// Python binding of the fitter: the same engine and the same JSON as `roadbrdf fit`.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "binding.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/models/registry.h"

namespace py = pybind11;

namespace roadbrdf::python {

namespace {
int call_counter = 0;
}  // namespace

void bind_fitting(py::module_& m) {
  // Returns the fit file's JSON text (the Python side parses it), and writes the file if asked.
  m.def(
      "fit",
      [](const DoubleArray& angles, const DoubleArray& wavelengths, const DoubleArray& brdf, const py::object& sigma,
         const std::map<std::string, std::string>& metadata, const std::string& convention,
         const std::vector<std::string>& models, const OptionSet& model_options, const std::vector<std::string>& shared,
         const std::map<std::string, double>& fixed, const std::map<std::string, double>& start,
         const std::string& loss, const std::string& robust, bool use_sigma, bool solid_angle_weights, int multistart,
         unsigned seed, const std::string& wavelength_selection, int threads, const std::string& output) {
        SpectralDataset data = dataset_from_arrays(angles, wavelengths, brdf, sigma, metadata, convention);
        if (!wavelength_selection.empty()) {
          data = subset_wavelengths(data, select_wavelengths(data.wavelengths, wavelength_selection));
        }
        FitOptions options;
        options.loss = fit_loss_from_string(loss);
        if (!robust.empty() && robust != "none") robust_loss_from_string(robust, options.robust, options.robust_scale);
        options.use_sigma = use_sigma;
        options.solid_angle_weights = solid_angle_weights;
        options.fixed = fixed;
        options.start = start;
        options.shared = shared;
        options.multistart = multistart;
        options.seed = seed;
        options.threads = threads;
        std::vector<FitResult> results;
        {
          py::gil_scoped_release release;
          for (const std::string& name : models) {
            // Options apply to every model that declares them (as on the command line).
            OptionSet declared;
            const auto probe = make_model(name);
            for (const auto& [key, value] : model_options) {
              for (const auto& o : probe->description().options) {
                if (o.name == key) declared[key] = value;
              }
            }
            const auto model = make_model(name, declared);
            results.push_back(fit_model(*model, data, options));
          }
        }
        // The text returned is exactly the fit file `roadbrdf fit` writes (written to a temporary
        // file when no output is asked for).
        std::string path = output;
        std::string temporary;
        if (path.empty()) {
          temporary = (std::filesystem::temp_directory_path() /
                       ("roadbrdf-fit-" + std::to_string(::getpid()) + "-" + std::to_string(++call_counter) + ".json"))
                          .string();
          path = temporary;
        }
        write_fit_file(path, results);
        std::ifstream in(path);
        std::stringstream text;
        text << in.rdbuf();
        if (!temporary.empty()) std::filesystem::remove(temporary);
        return text.str();
      });
}

}  // namespace roadbrdf::python
