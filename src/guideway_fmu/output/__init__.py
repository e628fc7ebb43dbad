"""What the commands write for a person to read beside their data: static HTML pages (``pages``)."""
