"""Command modules of the `assistbot` CLI (see `assistbot.cli`)."""
