"""Benchmarks (never collected as tests): run with ``zwidth bench [--quick]``."""
