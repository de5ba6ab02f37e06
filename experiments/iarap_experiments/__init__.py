"""The experiments report of the iARAP paper, driven through the `iarap` CLI (see experiments/README.md)."""
