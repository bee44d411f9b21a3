"""textX's front doors: the languages and generators registered for textX's own commands."""
