"""app.panels."""
