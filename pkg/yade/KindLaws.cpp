// SPDX-License-Identifier: GPL-2.0-or-later
#include "KindLaws.hpp"

namespace yade {
namespace core = swelldem::core;

KindLaws::Entry* KindLaws::find(const ContactKind& kind) const
{
	for (Entry* e = head_.load(std::memory_order_acquire); e; e = e->next)
		if (e->kind == &kind && e->instance == kind.instance()) return e;
	return nullptr;
}

KindLaws::Entry& KindLaws::entry(const ContactKind& kind)
{
	if (Entry* e = find(kind)) return *e;
	auto e      = std::make_unique<Entry>();
	e->kind     = &kind;
	e->instance = kind.instance();
	e->revision = -1;
	e->next     = head_.load(std::memory_order_relaxed);
	head_.store(e.get(), std::memory_order_release);
	entries_.push_back(std::move(e));
	return *entries_.back();
}

void KindLaws::build(Entry& e, const ContactKind& kind, const core::ContactKindParams& p)
{
	auto law = std::make_unique<core::ContactLaw>(p, window.shortestLag, window.longestLag);
	if (window.end > 0) law->beginStep(window.start, window.end);
	else
		law->beginStep(28.0, 28.0);
	e.revision = kind.revision();
	e.law.store(law.get(), std::memory_order_release);
	e.laws.push_back(std::move(law));
}

core::ContactLaw& KindLaws::lawFor(const ContactKind& kind)
{
	// Under a log-time solver (a step begun) a change of the kind waits for the next step.
	if (const Entry* e = find(kind))
		if (core::ContactLaw* law = e->law.load(std::memory_order_acquire))
			if (window.serial > 0 || e->revision == kind.revision()) return *law;
	std::lock_guard<std::mutex> lock(mutex_);
	Entry&                      e = entry(kind);
	if (!e.law.load(std::memory_order_relaxed) || (window.serial == 0 && e.revision != kind.revision())) build(e, kind, kind.params());
	return *e.law.load(std::memory_order_relaxed);
}

void KindLaws::beginStep(const std::vector<const ContactKind*>& kinds, Real shortestLag, Real longestLag, Real tPrev, Real t)
{
	std::lock_guard<std::mutex> lock(mutex_);
	for (const ContactKind* k : kinds)
		entry(*k);
	const bool lagsChanged = shortestLag != window.shortestLag || longestLag != window.longestLag;
	window.shortestLag     = shortestLag;
	window.longestLag      = longestLag;
	window.start           = tPrev;
	window.end             = t;
	++window.serial;
	for (Entry* e = head_.load(std::memory_order_relaxed); e; e = e->next) {
		// The kinds of this scene only: a kind no contact uses any more may be gone.
		if (std::find(kinds.begin(), kinds.end(), e->kind) == kinds.end() || e->instance != e->kind->instance()) continue;
		core::ContactLaw* law = e->law.load(std::memory_order_relaxed);
		const auto        p   = e->kind->params();
		if (law && !lagsChanged && p == law->params()) {
			law->beginStep(tPrev, t);
			e->revision = e->kind->revision();
			continue;
		}
		const size_t hidden = law ? law->chainSize() : 0;
		build(*e, *e->kind, p);
		const size_t now = e->law.load(std::memory_order_relaxed)->chainSize();
		if (law && window.serial > 1 && now != hidden)
			throw std::invalid_argument("swelldem: ContactKind '" + e->kind->name + "': this change gives its Kelvin chain "
			                            + std::to_string(now) + " units instead of "
			                            + std::to_string(hidden)
			                            + " while its contacts have a creep history; allowed during a run: changes that keep the chain "
			                              "(behaviour, kelvinUnitsPerDecade and the lags as they were)");
	}
}

} // namespace yade
