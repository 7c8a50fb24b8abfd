"""zwidth application: command line and Qt GUI (the only part that imports Qt)."""
