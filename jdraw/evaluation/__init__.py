"""Metrics, evaluation runs and the results tables."""
