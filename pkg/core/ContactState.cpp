// SPDX-License-Identifier: GPL-2.0-or-later
// ContactState is a plain aggregate; this file keeps the one-concept-per-file-pair layout.
#include "core/ContactState.hpp"
