"""Discrepancy workflow: find, name and close the gap between a measured run and the model."""
