//! Lengths for tidy's checks 6 and 7: the functions of non-test code and the inline
//! `#[cfg(test)]` modules of a source file, measured on the syntax tree that `syn` parses (so
//! braces in strings, characters, comments, raw strings and attributes count for nothing).
//!
//! A function runs from the line of its `fn` keyword to the line of its closing brace, both
//! counted (its doc comment and attributes are not); a test module from the line of its `mod`
//! keyword to that of its closing brace. Functions are named by the impl, trait or function
//! they sit in (`AdhesiveSolver::step`, `outer::inner`); a nested function counts in its own
//! right and inside the function around it. Test code is skipped: items marked
//! `#[cfg(test)]` (or `#[cfg(all(test, …))]`) and functions marked `#[test]`.

use proc_macro2::Span;
use syn::visit::{self, Visit};
use syn::{Attribute, Block, ImplItemFn, Item, ItemFn, ItemImpl, ItemMod, ItemTrait, Signature};

/// The longest function of non-test code, in lines.
pub const MAX_FUNCTION_LINES: usize = 150;

/// The longest inline `#[cfg(test)]` module, in lines; longer ones go in their own file
/// (`#[cfg(test)] mod tests;` with the file at `src/<module>/tests.rs`).
pub const MAX_TEST_MODULE_LINES: usize = 300;

/// An item and its length: the line it starts on (1-based), its name and its lines.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Measured {
    /// The line of the `fn` or `mod` keyword, 1-based.
    pub line: usize,
    /// The function's path within the file (`Type::method`) or the module's name.
    pub name: String,
    /// Lines from the keyword to the closing brace, both counted.
    pub lines: usize,
}

/// What one file holds: its non-test functions, its inline test modules, and the names of the
/// test modules it declares with a file of their own (`#[cfg(test)] mod tests;`).
#[derive(Debug, Default)]
pub struct Lengths {
    /// Every function (free, method, trait default, nested) outside test code.
    pub functions: Vec<Measured>,
    /// Every inline module marked `#[cfg(test)]`.
    pub test_modules: Vec<Measured>,
    /// The names of the modules declared `#[cfg(test)] mod name;`.
    pub test_module_files: Vec<String>,
}

/// The lengths of the items of the Rust source `text`, or the parse error.
pub fn measure(text: &str) -> syn::Result<Lengths> {
    let file = syn::parse_file(text)?;
    let mut visitor = Visitor::default();
    visitor.visit_file(&file);
    Ok(visitor.out)
}

#[derive(Default)]
struct Visitor {
    /// The impls, traits and functions around the item being visited.
    scope: Vec<String>,
    out: Lengths,
}

impl Visitor {
    fn function(&mut self, sig: &Signature, block: &Block) {
        let name = sig.ident.to_string();
        let start = sig.fn_token.span.start().line;
        let end = close_line(block.brace_token.span.close());
        let path = self
            .scope
            .iter()
            .cloned()
            .chain(std::iter::once(name))
            .collect::<Vec<_>>()
            .join("::");
        self.out.functions.push(Measured {
            line: start,
            name: path,
            lines: end + 1 - start,
        });
    }

    fn test_module(&mut self, module: &ItemMod) {
        match &module.content {
            Some((brace, _)) => {
                let start = module.mod_token.span.start().line;
                let end = close_line(brace.span.close());
                self.out.test_modules.push(Measured {
                    line: start,
                    name: module.ident.to_string(),
                    lines: end + 1 - start,
                });
            }
            None => self.out.test_module_files.push(module.ident.to_string()),
        }
    }
}

fn close_line(span: Span) -> usize {
    span.end().line
}

impl<'ast> Visit<'ast> for Visitor {
    fn visit_item(&mut self, item: &'ast Item) {
        if let Item::Mod(module) = item
            && is_test(&module.attrs)
        {
            self.test_module(module);
            return;
        }
        if item_attrs(item).is_some_and(is_test) {
            return;
        }
        visit::visit_item(self, item);
    }

    fn visit_item_fn(&mut self, f: &'ast ItemFn) {
        self.function(&f.sig, &f.block);
        self.scope.push(f.sig.ident.to_string());
        visit::visit_item_fn(self, f);
        self.scope.pop();
    }

    fn visit_impl_item_fn(&mut self, f: &'ast ImplItemFn) {
        if is_test(&f.attrs) {
            return;
        }
        self.function(&f.sig, &f.block);
        self.scope.push(f.sig.ident.to_string());
        visit::visit_impl_item_fn(self, f);
        self.scope.pop();
    }

    fn visit_trait_item_fn(&mut self, f: &'ast syn::TraitItemFn) {
        if is_test(&f.attrs) {
            return;
        }
        if let Some(block) = &f.default {
            self.function(&f.sig, block);
        }
        self.scope.push(f.sig.ident.to_string());
        visit::visit_trait_item_fn(self, f);
        self.scope.pop();
    }

    fn visit_item_impl(&mut self, i: &'ast ItemImpl) {
        self.scope.push(type_name(&i.self_ty));
        visit::visit_item_impl(self, i);
        self.scope.pop();
    }

    fn visit_item_trait(&mut self, t: &'ast ItemTrait) {
        self.scope.push(t.ident.to_string());
        visit::visit_item_trait(self, t);
        self.scope.pop();
    }

    fn visit_item_mod(&mut self, m: &'ast ItemMod) {
        self.scope.push(m.ident.to_string());
        visit::visit_item_mod(self, m);
        self.scope.pop();
    }
}

/// The last name of a type's path (`Operator` for `crate::Operator<T>`), else `_`.
fn type_name(ty: &syn::Type) -> String {
    match ty {
        syn::Type::Path(p) => p
            .path
            .segments
            .last()
            .map(|s| s.ident.to_string())
            .unwrap_or_else(|| "_".to_owned()),
        _ => "_".to_owned(),
    }
}

/// The attributes of the items that carry them.
fn item_attrs(item: &Item) -> Option<&[Attribute]> {
    Some(match item {
        Item::Const(i) => &i.attrs,
        Item::Enum(i) => &i.attrs,
        Item::ExternCrate(i) => &i.attrs,
        Item::Fn(i) => &i.attrs,
        Item::ForeignMod(i) => &i.attrs,
        Item::Impl(i) => &i.attrs,
        Item::Macro(i) => &i.attrs,
        Item::Mod(i) => &i.attrs,
        Item::Static(i) => &i.attrs,
        Item::Struct(i) => &i.attrs,
        Item::Trait(i) => &i.attrs,
        Item::TraitAlias(i) => &i.attrs,
        Item::Type(i) => &i.attrs,
        Item::Union(i) => &i.attrs,
        Item::Use(i) => &i.attrs,
        _ => return None,
    })
}

/// Whether the attributes mark test code: `#[test]`, `#[cfg(test)]` or `#[cfg(all(test, …))]`.
fn is_test(attrs: &[Attribute]) -> bool {
    attrs.iter().any(|attr| {
        if attr.path().is_ident("test") {
            return true;
        }
        if !attr.path().is_ident("cfg") {
            return false;
        }
        let Ok(list) = attr.meta.require_list() else {
            return false;
        };
        let tokens: Vec<String> = list
            .tokens
            .clone()
            .into_iter()
            .map(|t| t.to_string())
            .collect();
        match tokens.as_slice() {
            [only] => only == "test",
            [all, group] if all == "all" => group
                .trim_matches(|c| c == '(' || c == ')')
                .split(',')
                .any(|p| p.trim() == "test"),
            _ => false,
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `n` lines of body, each a statement.
    fn body(n: usize) -> String {
        (0..n).map(|i| format!("    let _x{i} = {i};\n")).collect()
    }

    #[test]
    fn functions_are_measured_from_fn_to_the_closing_brace() {
        // Braces in strings, raw strings, characters and comments, and attributes, count for
        // nothing.
        let text = format!(
            "//! Doc.\n/// Item doc.\n#[inline]\npub fn long() {{\n{}    let _s = \"}}}}\";\n    \
             let _r = r#\"{{\"}}\"#;\n    let _c = '}}';\n    // }}\n    /* }} */\n}}\n",
            body(3)
        );
        let lengths = measure(&text).unwrap();
        assert_eq!(
            lengths.functions,
            vec![Measured {
                line: 4,
                name: "long".to_owned(),
                lines: 10
            }]
        );
    }

    #[test]
    fn methods_nested_functions_and_trait_defaults_are_named_by_their_scope() {
        let text = "//! Doc.\nstruct S;\nimpl S {\n    fn m(&self) {\n        fn inner() {}\n    \
                    }\n}\ntrait T {\n    fn d(&self) {}\n    fn r(&self);\n}\n";
        let names: Vec<String> = measure(text)
            .unwrap()
            .functions
            .into_iter()
            .map(|f| f.name)
            .collect();
        assert_eq!(names, ["S::m", "S::m::inner", "T::d"]);
    }

    #[test]
    fn test_code_is_skipped_and_test_modules_measured() {
        let text = format!(
            "//! Doc.\nfn kept() {{}}\n#[test]\nfn t() {{}}\n#[cfg(test)]\nfn helper() {{}}\n\
             #[cfg(all(test, unix))]\nfn unix_helper() {{}}\n#[cfg(not(test))]\nfn real() {{}}\n\
             #[cfg(test)]\nmod tests {{\n    fn inside() {{\n{}    }}\n}}\n#[cfg(test)]\nmod more;\n",
            body(4)
        );
        let lengths = measure(&text).unwrap();
        let names: Vec<&str> = lengths.functions.iter().map(|f| f.name.as_str()).collect();
        assert_eq!(names, ["kept", "real"]);
        assert_eq!(
            lengths.test_modules,
            vec![Measured {
                line: 12,
                name: "tests".to_owned(),
                lines: 8
            }]
        );
        assert_eq!(lengths.test_module_files, ["more"]);
    }

    #[test]
    fn a_file_that_does_not_parse_is_an_error() {
        assert!(measure("fn broken( {").is_err());
    }
}
