# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Load the default recipe and the user's overlays."""

from pathlib import Path

from colcon_wasm import resources
from colcon_wasm.recipe import yaml_lines
from colcon_wasm.recipe.spec import check_recipe_data
from colcon_wasm.recipe.spec import Recipe
from colcon_wasm.recipe.spec import RecipeError
import yaml

__all__ = ['DEFAULT_RECIPE', 'load_recipe', 'Recipe', 'RecipeError']

"""The recipe used when the user gives none."""
DEFAULT_RECIPE = 'humble.yaml'


def default_recipe_path():
    """Get the path of the default recipe shipped with colcon-wasm."""
    return resources.file('recipes', DEFAULT_RECIPE)


def load_recipe_file(path):
    """
    Load and check one recipe file.

    :param path: the file
    :returns: the checked sections
    :raises RecipeError: for a missing file, a YAML syntax error or a schema
      violation, naming the file and line
    """
    path = Path(path).resolve()
    try:
        text = path.read_text()
    except OSError as e:
        raise RecipeError(f"cannot read recipe '{path}': {e.strerror}") \
            from e
    try:
        data = yaml_lines.load(text)
    except yaml.YAMLError as e:
        mark = getattr(e, 'problem_mark', None)
        line = f':{mark.line + 1}' if mark else ''
        problem = getattr(e, 'problem', None) or str(e)
        raise RecipeError(f'{path}{line}: invalid YAML: {problem}') from e
    return check_recipe_data(path, data)


def load_recipe(overlays=(), *, base=None):
    """
    Load the default recipe and apply overlays in order.

    :param overlays: paths of the user's `--wasm-recipe` files
    :param base: the base recipe path (default: the shipped humble.yaml)
    :returns: the :class:`Recipe`
    :raises RecipeError: see :func:`load_recipe_file`
    """
    recipe = Recipe()
    for path in [base or default_recipe_path()] + list(overlays or ()):
        recipe.merge(load_recipe_file(path))
        recipe.files.append(Path(path).resolve())
    return recipe
