"""Blender test configuration: the ONE place that lists generators allowed
to be missing from the library under test, each with the work that
builds it. A generator missing from the library and not listed here makes
its tests FAIL. The lead removes entries as generators land."""
EXPECTED_MISSING = {
}
