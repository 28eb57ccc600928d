"""The transfer study: events memorized in one world used for trials in another
(docs/transfer.md).

- matrix.py: the transfer spec, the worlds, each cell run as a sweep.
- report.py: the table and heat map from the cells' records.
- diagnosis.py: which channel's Eq. 3 score falls short, offline."""
