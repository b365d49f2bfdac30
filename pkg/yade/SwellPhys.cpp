// SPDX-License-Identifier: GPL-2.0-or-later
#include "SwellPhys.hpp"

namespace yade {
namespace core = swelldem::core;

core::ContactGeometry SwellPhys::geometry() const
{
	core::ContactGeometry g;
	g.area                    = area;
	g.length                  = length;
	g.swellingDisplacementInf = swellDispInf;
	return g;
}

void SwellPhys::toCore(core::ContactState& s) const
{
	s.committed.Fn     = committedFn;
	s.committed.Fs     = committedFs;
	s.committed.FnHat  = committedFnHat;
	s.committed.broken = committedBroken;
	s.committed.mode   = core::FailureMode(committedMode);
	s.trial.Fn         = Fn;
	s.trial.Fs         = Fs;
	s.trial.FnHat      = FnHat;
	s.trial.broken     = broken;
	s.trial.mode       = core::FailureMode(failureMode);
	s.gamma.assign(gamma.begin(), gamma.end());
	s.kn        = kn;
	s.ks        = ks;
	s.duOffsetN = duOffsetN;
	s.duOffsetS = duOffsetS;
}

void SwellPhys::fromCore(const core::ContactState& s)
{
	committedFn     = s.committed.Fn;
	committedFs     = s.committed.Fs;
	committedFnHat  = s.committed.FnHat;
	committedBroken = s.committed.broken;
	committedMode   = int(s.committed.mode);
	Fn              = s.trial.Fn;
	Fs              = s.trial.Fs;
	FnHat           = s.trial.FnHat;
	broken          = s.trial.broken;
	failureMode     = int(s.trial.mode);
	gamma.assign(s.gamma.begin(), s.gamma.end());
	kn        = s.kn;
	ks        = s.ks;
	duOffsetN = s.duOffsetN;
	duOffsetS = s.duOffsetS;
}

} // namespace yade
