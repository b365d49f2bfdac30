// SPDX-License-Identifier: GPL-2.0-or-later
// Which contact kind two particles make, from their materials: the one rule, used by the plugin's
// Ip2 (contacts made during a run) and by the mesostructure generator (an assembly's contacts,
// without YADE, through libswelldem_geom's swd_pair_kinds). Header only, so that the geometry
// library takes it without linking the physics core.
#pragma once

namespace swelldem::core {

// The ids are swelldem.paper's KIND_IDS and STRUCTURE_KIND_IDS (ContactKind.kindId, Assembly.kind).
enum class PairKind { Mortar = 0, Itz = 1, Agg = 2, Platen = 3, Steel = 4, Bond = 5 };
constexpr int kPairKinds = 6;

// What of a particle's material the rule reads (ConcreteMat's aggregateId, platen and steel).
struct PairMaterial {
    int  aggregateId = -1; // -1 mortar, >= 0 one coarse aggregate
    bool platen      = false;
    bool steel       = false;
};

// Platens first (a bar's end may touch one), then steel, then the concrete's own kinds: two
// discs of one aggregate are inside it (AGG), a mortar disc or another aggregate across an
// interface (ITZ).
inline PairKind pairKind(const PairMaterial& a, const PairMaterial& b)
{
    if (a.platen || b.platen) return PairKind::Platen;
    if (a.steel && b.steel) return PairKind::Steel;
    if (a.steel || b.steel) return PairKind::Bond;
    if (a.aggregateId < 0 && b.aggregateId < 0) return PairKind::Mortar;
    return a.aggregateId >= 0 && b.aggregateId >= 0 && a.aggregateId == b.aggregateId ? PairKind::Agg : PairKind::Itz;
}

} // namespace swelldem::core
