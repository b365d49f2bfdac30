# SPDX-License-Identifier: GPL-2.0-or-later
"""Access to YADE with the swelldem plugin loaded, with one clear error when it is not."""


def require(user):
    """(yade, yade.wrapper) when running inside YADE with the plugin; else RuntimeError naming `user`."""
    try:
        import yade
        from yade import wrapper
        wrapper.AdrLogTimeIntegrator
        wrapper.Law2_ScGeom_SwellPhys_AgingSwelling
    except (ImportError, AttributeError) as e:
        raise RuntimeError(f"{user} needs YADE with the swelldem plugin: run it with scripts/yade-swelldem") from e
    return yade, wrapper
