# SPDX-License-Identifier: GPL-2.0-or-later
"""swelldem.dem: everything that talks to YADE and the swelldem plugin.

* :mod:`.scene`: contact kinds from the paper's data, discs, engines, the solver chosen by name
  (:func:`make_solver`), the one scene builder (:func:`build_scene`), :func:`run_to_end`;
* :mod:`.meso_scene`: a :class:`swelldem.meso.Assembly` as a scene (:func:`to_yade`), per-contact
  swelling and the gel pockets of ASR with reactive coarse aggregate;
* :mod:`.recorder`: what a swelling test records after every converged physical step (the
  solver's ``stepHook``), VTK export, and :func:`standard_outputs`, the same outputs for a scene
  of one's own;
* :mod:`.uniaxial`: displacement-controlled uniaxial tension or compression between two bands of
  discs (virtual tests of a specimen's stiffness and strength).

The modules import YADE only when a function needs it, and then through
:func:`swelldem.plugin.require`: in plain Python they import, and their functions raise
:class:`swelldem.plugin.YadeUnavailableError` with the command to use instead.
"""
from ..plugin import YadeUnavailableError
from .meso_scene import MAX_GAP_RATIO, YadeScene, set_contact_swelling, set_gel_pockets, to_yade
from .recorder import standard_outputs
from .scene import (BEHAVIOURS, SOLVERS, build_scene, check_solver_settings, concrete_ip2, contact_kind, disc, engines,
                    functor_kinds, kind_setting_names, kind_settings, make_solver, reset_keeping_tags,
                    run_chunk_quietly, run_to_end, scene_law, solver_defaults, solver_setting_names, solver_settings)

__all__ = ["BEHAVIOURS", "MAX_GAP_RATIO", "SOLVERS", "YadeScene", "YadeUnavailableError", "build_scene", "concrete_ip2", "contact_kind",
           "disc", "check_solver_settings", "engines", "functor_kinds", "kind_setting_names", "kind_settings",
           "make_solver", "reset_keeping_tags", "run_chunk_quietly", "run_to_end", "scene_law", "set_contact_swelling", "set_gel_pockets", "solver_defaults",
           "solver_setting_names", "solver_settings", "standard_outputs", "to_yade"]
