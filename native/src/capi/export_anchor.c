/* Gives the shared library one source of its own; every symbol comes from softshadow_static. */
/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "softshadow/softshadow.h"
