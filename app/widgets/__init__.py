"""Small reusable parameter widgets, one per file.  Widgets never compute and never write other
widgets: they show model fields and send edits to the :class:`~app.commands.Editor`."""
