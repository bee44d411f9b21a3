"""``lightrocks studio``: a local page that shows the models' diagrams with the findings of
``check`` on them and edits them through the language's parser and pretty printer."""
