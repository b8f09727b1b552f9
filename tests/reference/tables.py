"""Reading the CSV tables a command writes, for the tests that check them."""

import csv

__all__ = ["csv_rows"]


def csv_rows(path) -> list[dict]:
    """The rows of a CSV file with a header, as dicts of strings."""
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))
