"""The transfer study: events memorized in one world used for trials in another (matrix.py:
the spec, the worlds and running each cell as a sweep; report.py: the table and heat map
from the records). docs/transfer.md."""
