# SPDX-License-Identifier: GPL-2.0-or-later
"""The servo simulator: scenarios, closed-loop runs and batch trials."""
from ._icgp.servo import Scenario, load_scenario  # noqa: F401
