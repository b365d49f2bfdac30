# SPDX-License-Identifier: GPL-2.0-or-later
"""Access to YADE with the swelldem plugin loaded, with one clear error when it is not."""

#: The plugin classes whose presence proves that the plugin is loaded.
PLUGIN_CLASSES = ("ConcreteMat", "ContactKind", "SwellPhys", "Ip2_ConcreteMat_ConcreteMat_SwellPhys",
                  "Law2_ScGeom_SwellPhys_AgingSwelling", "AdrLogTimeIntegrator")


class YadeUnavailableError(RuntimeError):
    """Raised when YADE-facing code (swelldem.dem, swelldem.scenario.run) runs outside YADE or
    without the swelldem plugin."""


def require(user):
    """(yade, yade.wrapper) when running inside YADE with the plugin; else YadeUnavailableError naming `user`."""
    try:
        import yade
        from yade import wrapper
    except ImportError as e:
        raise YadeUnavailableError(
            f"{user} needs YADE with the swelldem plugin: run the script with scripts/yade-swelldem "
            f"(e.g. scripts/yade-swelldem -n -x script.py), not with plain python ({e})") from None
    missing = [c for c in PLUGIN_CLASSES if not hasattr(wrapper, c)]
    if missing:
        raise YadeUnavailableError(
            f"{user}: YADE runs but the swelldem plugin is not loaded (missing {', '.join(missing)}); start YADE "
            "through scripts/yade-swelldem, which points YADE_PREFIX at the build's overlay prefix")
    return yade, wrapper
