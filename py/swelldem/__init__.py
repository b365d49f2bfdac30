# SPDX-License-Identifier: GPL-2.0-or-later
"""swelldem: concrete swelling (ISR, ASR) at the mesoscale with 2D particle models in YADE.

The compiled parts live in the CMake build folder (``build/`` at the top of the
repository unless ``SWELLDEM_BUILD_DIR`` says otherwise); see ``swelldem.paths``.
"""
#: The plugin's version, its one home: CMake reads it at configure time and the plugin records it in
#: every saved scene; a scene is loaded only by the version that saved it (docs/reliability.md).
#: Raise it whenever a saved attribute of a plugin class changes.
__version__ = "0.2.0"
