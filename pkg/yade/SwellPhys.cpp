// SPDX-License-Identifier: GPL-2.0-or-later
#include "SwellPhys.hpp"
#include "LogTimeSolver.hpp"
#include "core/Validate.hpp"

namespace yade {

void SwellPhys::postLoad()
{
	// A contact made by the Ip2 gets its geometry right after; zero means "not set yet".
	if (area != 0) swelldem::core::requirePositive("SwellPhys.area [m2]", area);
	if (length != 0) swelldem::core::requirePositive("SwellPhys.length [m]", length);
	if (!(swellDispInf < 0)) swelldem::core::requireNonNegative("SwellPhys.swellDispInf [m]", swellDispInf);
}

void SwellPhys::checkObject(const char*, const shared_ptr<ContactKind>& value) const
{
	// Every user of a contact (the law, the solvers' set-up, commit and breaks, the implicit solver's
	// tangent) reads its kind: Python cannot take it away. (A default-made or loaded SwellPhys may have
	// none; the law guards it, and the log-time solvers refuse such a contact before their first step.)
	if (!value)
		throw std::invalid_argument("swelldem: SwellPhys.kind = None is out of range; allowed: a ContactKind (a contact cannot be left "
		                            "without its kind; assign another ContactKind to change it)");
	// A contact that has run physical steps under a log-time solver takes only a kind the solver has
	// begun steps on: a kind new to the scene has no law for the current step (the contact would
	// compute it at the default age of 28 days, not at the step's times) until the next step begins.
	if (stepSerial > 0 && value->stepSerial == 0)
		throw std::invalid_argument("swelldem: SwellPhys.kind = ContactKind '" + value->name
		                            + "' is out of range; allowed: a kind of this running scene (one its log-time solver has begun "
		                              "steps on); to change a kind during a run, change its parameters (they apply from the next step)");
}

void SwellPhys::startAnotherRun(const boost::python::object& given)
{
	// Any value is taken, so that a wrong one gets the plugin's message, not a signature mismatch.
	boost::python::extract<shared_ptr<ContactKind>> x(given);
	const shared_ptr<ContactKind> value = x.check() ? x() : shared_ptr<ContactKind>();
	if (!value)
		throw std::invalid_argument("swelldem: SwellPhys.startAnotherRun(kind = " + string(boost::python::extract<string>(boost::python::str(given)))
		                            + "): kind is out of range; allowed: a ContactKind");
	// Under a solver that has begun its steps a new kind would have no law for the current step (see
	// checkObject): another run starts on a scene whose log-time solvers are gone or not begun.
	namespace bp = boost::python;
	const bp::object engines = bp::import("yade").attr("Omega")().attr("engines");
	for (long i = 0; i < bp::len(engines); ++i) {
		bp::extract<const LogTimeSolver*> e(engines[i]);
		if (e.check() && e() && !e()->times.empty())
			throw std::invalid_argument("swelldem: SwellPhys.startAnotherRun(kind '" + value->name + "') refused: the scene's "
			                            + e()->getClassName() + " has begun its steps (step " + std::to_string(e()->step) + "/"
			                            + std::to_string(e()->nSteps()) + "); allowed: on a scene whose log-time solvers have not begun "
			                              "(take the saved run's solver out of O.engines first)");
	}
	kind = value;
	// -1 matches no kind's step serial: the contact sets itself up at kind's next step, whatever
	// serial the saved run had reached; until its solver begins that step the law holds it at no force.
	stepSerial = -1;
}

} // namespace yade
