// The albedo request's field table (core/request_fields.h) and its task: the model source resolved
// by the one resolver of model arguments, then the albedos of report.cpp.
#include "roadbrdf/albedo/report.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/modelfile/model_source.h"

namespace roadbrdf::albedo {

namespace {

using R = AlbedoRequest;

const RequestField<R> kFields[] = {
    {"model", "MODEL", "", "Fit file (FIT.json), MIX.json or model name, e.g. oren-nayar+torrance-sparrow", &R::model,
     FileRole::input},
    {"parameters", "-p,--parameter", "", "Model parameter NAME=VALUE (repeatable); defaults otherwise", &R::parameters},
    {"options", "--option", "", "Model option NAME=VALUE (repeatable), e.g. distribution=ggx", &R::options},
    {"fit", "--fit", "",
     "Which fit of FIT.json (its model name, e.g. lambert+torrance-sparrow) or which method of a MIX.json "
     "(default: the best-ranked)",
     &R::fit},
    {"sun_zenith", "--sun-zenith", "deg",
     "Sun zenith: D, D1,D2,..., START:STOP:STEP (both ends included) or a mix (default 30)", &R::sun_zenith_deg},
    {"sun_azimuth", "--sun-azimuth", "deg", "Sun azimuth for anisotropic models (default 0)", &R::sun_azimuth_deg},
    {"azimuth_mean", "--azimuth-mean", "", "Anisotropic models: average black-sky over the sun azimuth",
     &R::azimuth_mean},
    {"diffuse_fraction", "--diffuse-fraction", "",
     "Diffuse fraction D for blue-sky: a number in [0, 1] or a CSV wavelength_nm,diffuse_fraction",
     &R::diffuse_fraction, FileRole::input},
    {"atmosphere", "--atmosphere", "",
     "spectrl2[:aod=0.1,water=1.42,ozone=0.344,pressure=101325,alpha=1.14,ground=0.2,day=81]: D(lambda) and the "
     "broadband weights from the SPECTRL2 clear-sky model (pressure in Pa, water in cm, ozone in atm-cm)",
     &R::atmosphere},
    {"spectrum", "--spectrum", "",
     "Broadband weighting: astm-g173-global (default), astm-g173-direct or a CSV wavelength_nm,irradiance_W_m2_nm "
     "(default with an atmosphere: SPECTRL2 direct + diffuse)",
     &R::spectrum, FileRole::input},
    {"wavelengths", "--wavelengths", "nm",
     "Wavelengths of a fit file: LIST or START:STOP:STEP (both ends included), increasing", &R::wavelengths},
    {"illuminant", "--illuminant", "", "Also the luminous (V(lambda)-weighted) albedo: A, D65 or a file",
     &R::illuminant, FileRole::input},
    {"tolerance", "--tolerance", "", "Absolute quadrature tolerance per value", &R::tolerance},
    // A switch that is on by default: the command line's flag turns it off (request_options.h).
    {"uncertainty", "--no-uncertainty", "",
     "Standard uncertainties from a fit's parameter covariance; off: values only", &R::uncertainty},
    {"threads", "--threads", "", "Threads (default: all cores; the results do not depend on it)", &R::threads},
};

}  // namespace

std::span<const RequestField<AlbedoRequest>> AlbedoRequest::fields() { return kFields; }

std::string AlbedoResult::summary_text() const { return albedo_table(report); }

AlbedoResult albedo(const AlbedoRequest& request) {
  if (request.model.empty()) throw FieldError("model", "give a fit file, a MIX.json or a model name");
  request.validate();
  const ResolvedModel resolved = resolve_model(request.model, request.parameters, request.options, request.fit);
  AlbedoResult result;
  result.report = compute_albedo(resolved.model, request);
  for (const nlohmann::json& w : result.report.at("warnings")) {
    result.diagnostics.warn(w.at("kind").get<std::string>(), w.at("message").get<std::string>());
  }
  return result;
}

}  // namespace roadbrdf::albedo
