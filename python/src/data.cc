// The bindings of measured data: n,k files, spectra and data sets (core/io.h, dataset.h).
#include <pybind11/stl.h>

#include <utility>

#include "alloycolor/core/io.h"
#include "bindings.h"

namespace alloycolor::python {

namespace {

// [{"x_atomic", "x_given", "file", "path", "spectrum"}] (and "excluded": the reason, for a
// sample the manifest sets aside).
py::list SampleList(const std::vector<Sample>& samples) {
  py::list out;
  for (const Sample& s : samples) {
    py::dict r;
    r["x_atomic"] = s.x_atomic;
    r["x_given"] = s.x_given;
    r["file"] = s.file;
    r["path"] = s.path;
    r["spectrum"] = s.nk;
    if (!s.excluded.empty()) r["excluded"] = s.excluded;
    out.append(r);
  }
  return out;
}

}  // namespace

SpectrumClass BindData(py::module_& m) {
  m.def(
      "_read_nk",
      [](const std::string& path, const std::string& columns) {
        std::vector<std::string> warnings;
        const NkSpectrum nk = columns.empty()
                                  ? ReadNkFile(path, &warnings)
                                  : ReadNkFile(path, ParseNkColumns(columns), &warnings);
        return std::make_pair(nk, warnings);
      },
      py::arg("path"), py::arg("columns") = "");

  SpectrumClass spectrum(m, "_Spectrum");
  spectrum.def_readonly("source", &NkSpectrum::source)
      .def_property_readonly("lambda_nm", [](const NkSpectrum& s) { return ToArray(s.lambda_nm); })
      .def_property_readonly("n", [](const NkSpectrum& s) { return ToArray(s.n); })
      .def_property_readonly("k", [](const NkSpectrum& s) { return ToArray(s.k); });

  py::class_<Dataset>(m, "_Dataset")
      .def(py::init(&LoadDataset))
      .def_readonly("manifest_path", &Dataset::manifest_path)
      .def_readonly("name", &Dataset::name)
      .def_property_readonly("system", [](const Dataset& d) { return d.system.Name(); })
      .def_readonly("composition", &Dataset::composition)
      .def_readonly("warnings", &Dataset::warnings)
      .def_property_readonly("precision",
                             [](const Dataset& d) {
                               py::dict r;
                               r["n"] = d.precision_n;
                               r["k"] = d.precision_k;
                               return r;
                             })
      .def_property_readonly("x_atomic",
                             [](const Dataset& d) {
                               std::vector<double> xs;
                               for (const Sample& s : d.samples) xs.push_back(s.x_atomic);
                               return ToArray(xs);
                             })
      .def_property_readonly("samples", [](const Dataset& d) { return SampleList(d.samples); })
      .def_property_readonly("excluded", [](const Dataset& d) { return SampleList(d.excluded); })
      .def("parse_composition",
           [](const Dataset& d, const std::string& text) {
             return ParseComposition(text, d.system);
           })
      .def("sample_x",
           [](const Dataset& d, double x) -> py::object {
             const Sample* s = FindSample(d, x);
             return s ? py::cast(s->x_atomic) : py::none();
           })
      .def("without", [](const Dataset& d, const std::vector<double>& exclude_x) {
        return WithoutSamples(d, exclude_x);
      });

  return spectrum;
}

}  // namespace alloycolor::python
