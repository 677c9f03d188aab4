// SPDX-License-Identifier: GPL-2.0-or-later
// Stands first in the consumer's include path: yaml-cpp is icgp's private dependency, and a
// public header that brought it into a user's program would stop the build here.
#error "an installed icgp header includes yaml-cpp, which icgp links privately"
