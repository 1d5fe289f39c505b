// Python binding of mixing: the same library calls as `roadbrdf mix`, returning the MIX.json text.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "binding.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/mixing/mix_file.h"
#include "roadbrdf/mixing/mixing.h"
#include "roadbrdf/mixing/residual_file.h"

namespace py = pybind11;

namespace roadbrdf::python {

namespace {
int mix_counter = 0;
}  // namespace

void bind_mixing(py::module_& m) {
  m.def(
      "mix",
      [](const std::string& formulation_path, const std::string& data_path, const std::string& method, int folds,
         unsigned seed, bool per_wavelength, bool sum_to_one, std::optional<double> binder_coverage,
         std::optional<double> mastic_fraction, const std::string& reference_path, const std::string& output,
         bool use_sigma, const std::string& residuals) {
        using namespace mixing;
        std::vector<FileArgument> files_read = {
            {"formulation", formulation_path}, {"data", data_path}, {"reference", reference_path}};
        const std::vector<FileArgument> outputs = {{"output", output}, {"residuals", residuals}};
        check_distinct_files(files_read, outputs);
        const Formulation formulation = read_formulation(formulation_path);
        if (formulation.mastic) files_read.push_back({"mastic.fit of " + formulation_path, formulation.mastic->fit_path});
        for (const auto& c : formulation.components) {
          files_read.push_back({"fit of component '" + c.name + "'", c.fit_path});
        }
        check_distinct_files(files_read, outputs);
        const MixInputs inputs = load_mix_inputs(formulation);
        MixSettings settings;
        settings.binder_coverage = binder_coverage;
        settings.mastic_area_fraction = mastic_fraction;
        settings.per_wavelength = per_wavelength;
        settings.sum_to_one = sum_to_one;
        settings.use_sigma = use_sigma;
        if (!residuals.empty() && data_path.empty()) throw InputError("residuals needs data (held-out residuals)");
        const bool all = method == "all";
        const std::vector<Method> methods = all ? all_methods() : std::vector<Method>{method_from_string(method)};
        std::optional<SpectralDataset> data;
        if (!data_path.empty()) data = read_dataset(data_path);
        std::optional<SpectralModel> reference;
        if (!reference_path.empty()) {
          if (!data) throw InputError("reference needs data (the albedo is compared at the data's wavelengths)");
          reference = read_spectral_model_file(reference_path);
        }
        MixFileContent content;
        content.inputs = &inputs;
        content.data_path = data_path;
        content.folds = folds;
        {
          py::gil_scoped_release release;
          for (Method meth : methods) {
            if (!data && method_needs_data(meth) && all) continue;  // as the CLI: skipped without data
            try {
              if (data) {
                Comparison c = compare_method(inputs, meth, settings, *data, folds, seed,
                                              reference ? &*reference : nullptr);
                content.results.push_back(c.result);
                content.comparisons.push_back(std::move(c));
              } else {
                content.results.push_back(mix(inputs, meth, settings));
              }
            } catch (const InputError&) {
              if (!all) throw;
            }
          }
        }
        if (content.results.empty()) throw InputError("no mixing method could be applied to " + formulation_path);
        std::string path = output;
        std::string temporary;
        if (path.empty()) {
          temporary = (std::filesystem::temp_directory_path() /
                       ("roadbrdf-mix-" + std::to_string(::getpid()) + "-" + std::to_string(++mix_counter) + ".json"))
                          .string();
          path = temporary;
        }
        write_mix_file(path, content);
        if (!residuals.empty()) write_residual_file(residuals, *data, content.comparisons);
        std::ifstream in(path);
        std::stringstream text;
        text << in.rdbuf();
        if (!temporary.empty()) std::filesystem::remove(temporary);
        return text.str();
      },
      py::arg("formulation"), py::arg("data") = "", py::arg("method") = "all", py::arg("folds") = 5,
      py::arg("seed") = 1u, py::arg("per_wavelength") = false, py::arg("sum_to_one") = false,
      py::arg("binder_coverage") = py::none(), py::arg("mastic_fraction") = py::none(), py::arg("reference") = "",
      py::arg("output") = "", py::arg("use_sigma") = true, py::arg("residuals") = "");
  m.def("read_spectral_model_file", &mixing::read_spectral_model_file, py::arg("path"), py::arg("selection") = "");
}

}  // namespace roadbrdf::python
