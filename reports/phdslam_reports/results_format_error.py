"""The error of a results file that is missing, unreadable or malformed (no third-party imports,
so that the scripts without numpy raise it too)."""


class ResultsFormatError(ValueError):
    """A results file is missing, unreadable or malformed; the message names file and column."""
