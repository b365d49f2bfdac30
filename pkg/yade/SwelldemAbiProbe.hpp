// SPDX-License-Identifier: GPL-2.0-or-later
// A diagnostic engine that reads YADE's objects through swelldem's own declarations
// (pkg/yade/compat), so Python can compare them with what YADE's own accessors report.
// The ABI tests use it; users can run swelldem.abi.self_check() after a YADE upgrade.
#pragma once
#include "compat/Plugin.hpp"

namespace yade {

class SwelldemAbiProbe : public GlobalEngine {
public:
#define SWELLDEM_ABI_PROBE_ATTRS(X)                                                                                                                            \
	X(long, nCalls, 0, swelldem_attr::Result, "Number of times action() ran [-]")                                                                                                  \
	X(long, lastIter, -1, swelldem_attr::Result, "O.iter seen by the last action() [-]")                                                                                          \
	X(Real, lastTime, -1, swelldem_attr::Result, "O.time seen by the last action() [s of YADE time]")                                                                             \
	X(Real, lastDt, -1, swelldem_attr::Result, "O.dt seen by the last action() [s of YADE time]")                                                                                 \
	X(Real, totalMass, 0, swelldem_attr::Result, "Sum of the bodies' State.mass at the last action() [kg]")                                                                      \
	X(Real, kineticEnergy, 0, swelldem_attr::Result, "Translational kinetic energy of the bodies at the last action() [J]")
	SWELLDEM_CLASS(SwelldemAbiProbe, GlobalEngine,
	               "Reads scene, bodies, materials, interactions, engines and functors through swelldem's own declarations of "
	               "YADE's classes. Diagnostic only: it changes nothing in the scene.",
	               SWELLDEM_ABI_PROBE_ATTRS)
	virtual ~SwelldemAbiProbe() { }
	void action() override;
	void postLoad() { }

	boost::python::dict        readScene() const;
	static boost::python::dict readBody(const shared_ptr<Body>& b);
	static boost::python::dict readMaterial(const shared_ptr<Material>& m);
	static boost::python::dict readInteraction(const shared_ptr<Interaction>& i);
	static boost::python::dict readEngine(const shared_ptr<Engine>& e);
	static boost::python::dict readFunctor(const shared_ptr<Functor>& f);
	static boost::python::dict declaredLayout();

	template <class C> static void pyMethods(C& cls)
	{
		cls.def("readScene", &SwelldemAbiProbe::readScene, "Scene fields read through swelldem's declarations (dict).");
		cls.def("readBody", &SwelldemAbiProbe::readBody, "Body and State fields of a body (dict).").staticmethod("readBody");
		cls.def("readMaterial", &SwelldemAbiProbe::readMaterial, "Material fields (dict).").staticmethod("readMaterial");
		cls.def("readInteraction", &SwelldemAbiProbe::readInteraction, "Interaction, ScGeom and FrictPhys fields (dict).")
		        .staticmethod("readInteraction");
		cls.def("readEngine", &SwelldemAbiProbe::readEngine, "Engine fields (dict).").staticmethod("readEngine");
		cls.def("readFunctor", &SwelldemAbiProbe::readFunctor, "Functor fields (dict).").staticmethod("readFunctor");
		cls.def("declaredLayout", &SwelldemAbiProbe::declaredLayout, "sizeof and offsets of the declarations (dict of bytes).")
		        .staticmethod("declaredLayout");
	}
};

} // namespace yade
