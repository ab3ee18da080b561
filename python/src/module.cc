// The module alloycolor._alloycolor: each topic's functions and classes (bindings.h), the
// classes first that later topics add methods to.
#include "bindings.h"

PYBIND11_MODULE(_alloycolor, m) {
  namespace python = alloycolor::python;
  m.doc() = "Compiled core of the alloycolor package; use the alloycolor package itself.";
  python::BindErrors(m);
  python::BindRegistry(m);
  python::SpectrumClass spectrum = python::BindData(m);
  python::ModelClass model = python::BindModel(m);
  python::BindColour(m, spectrum, model);
  python::BindOutputs(m, spectrum, model);
  python::BindValidate(m);
}
