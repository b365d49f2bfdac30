# SPDX-License-Identifier: GPL-2.0-or-later
"""swelldem: concrete swelling (ISR, ASR) at the mesoscale with 2D particle models in YADE.

The compiled parts live in the CMake build folder (``build/`` at the top of the
repository unless ``SWELLDEM_BUILD_DIR`` says otherwise); see ``swelldem.paths``.
"""
__version__ = "0.1.0"
