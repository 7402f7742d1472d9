"""Shared by the exporters: the error type and the warning collector."""


class ExportError(Exception):
    """The scene cannot be rendered (no camera, nothing to render, ...); the message is shown to the user as is."""


class Warnings:
    """Collects user-facing warnings, each distinct message once (one warning per material, not per triangle)."""

    def __init__(self):
        self.messages = []
        self._seen = set()

    def add(self, message):
        if message not in self._seen:
            self._seen.add(message)
            self.messages.append(message)
