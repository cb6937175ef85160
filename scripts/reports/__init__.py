"""The sections of docs/RESULTS.md, one module each; scripts/report.py runs them."""
