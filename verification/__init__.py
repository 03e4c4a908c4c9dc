"""Verification report builders and benchmarks for dhfield (not part of the installed library)."""
