"""Built-in scenes shipped with the package."""
