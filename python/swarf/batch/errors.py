"""The error of a batch's input or its results folder."""


class BatchError(ValueError):
    """A sweep, job list, option or results folder that a batch cannot use; the
    message names the file, the field and what was expected."""
