// SPDX-License-Identifier: GPL-2.0-or-later
// The laws a run builds from its contact kinds: the physical step it has begun (serial, time
// window, the lags its Kelvin chains resolve) and one physics-core ContactLaw per kind, built for
// that step. A ContactKind is a table of parameters only, so one kind may serve any number of
// scenes; each scene's law functor (Law2_ScGeom_SwellPhys_AgingSwelling) owns a KindLaws, and the
// log-time solvers drive it at each step's start.
#pragma once
#include "ContactKind.hpp"
#include <algorithm>
#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

namespace yade {

/// The step a run has begun; saved with the law functor (its laws are rebuilt from it after O.load).
struct StepWindow {
	long serial      = 0;    // physical steps begun; a contact sets itself up when its own differs
	Real start       = 0;    // [day] start of the step begun (0: none, the laws act at age 28 days)
	Real end         = 0;    // [day] end of the step begun
	Real shortestLag = 1e-2; // [day] shortest load duration the Kelvin chains resolve (the first step)
	Real longestLag  = 1e5;  // [day] longest one (the run's span)
	template <class Archive> void serialize(Archive& ar, unsigned)
	{
		ar& boost::serialization::make_nvp("serial", serial);
		ar& boost::serialization::make_nvp("start", start);
		ar& boost::serialization::make_nvp("end", end);
		ar& boost::serialization::make_nvp("shortestLag", shortestLag);
		ar& boost::serialization::make_nvp("longestLag", longestLag);
	}
};

} // namespace yade
BOOST_CLASS_IMPLEMENTATION(yade::StepWindow, boost::serialization::object_serializable)
BOOST_CLASS_TRACKING(yade::StepWindow, boost::serialization::track_never)

namespace yade {

class KindLaws {
public:
	/// The step lives with the owner, which saves it.
	explicit KindLaws(StepWindow& w) : window(w) { }
	KindLaws(const KindLaws&) = delete;
	StepWindow& window;
	/// The law of `kind` for the step begun (thread-safe: the contact loops call it in parallel).
	/// Built at first use for the window; with no step begun (other integrators), built at age
	/// 28 days and again after a parameter of the kind changed. Throws std::invalid_argument for
	/// bad parameters (the error names the kind).
	swelldem::core::ContactLaw& lawFor(const ContactKind& kind);
	/// A log-time solver at a step's start (outside any parallel region): begins the step [tPrev, t]
	/// [day] on every law, rebuilding those whose kind changed since (or that are new), and on the
	/// laws of `kinds` (the scene's), so that bad parameters fail here. Throws std::invalid_argument
	/// for a Kelvin chain that would change under contacts with a creep history.
	void beginStep(const std::vector<const ContactKind*>& kinds, Real shortestLag, Real longestLag, Real tPrev, Real t);

private:
	struct Entry {
		const ContactKind*                                       kind;
		unsigned long                                            instance; // the kind's ContactKind::instance(): an address may be reused
		long                                                     revision; // the kind's revision the law was built from
		std::atomic<swelldem::core::ContactLaw*>                 law { nullptr };
		std::vector<std::unique_ptr<swelldem::core::ContactLaw>> laws; // the current one last; a replaced law may still be read by a running loop
		Entry*                                                   next = nullptr;
	};
	std::atomic<Entry*>                 head_ { nullptr }; // readers walk the list without the lock; entries are only added
	std::vector<std::unique_ptr<Entry>> entries_;
	std::mutex                          mutex_;
	Entry*                              find(const ContactKind& kind) const;
	Entry&                              entry(const ContactKind& kind); // under mutex_
	void                                build(Entry& e, const ContactKind& kind, const swelldem::core::ContactKindParams& p); // under mutex_
};

} // namespace yade
