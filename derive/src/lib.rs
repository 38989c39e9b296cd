//! `#[derive(Describe)]` and `#[derive(Params)]` for saltus closures.
//!
//! Use them through `saltus_core` (`use saltus_core::Describe;` brings both the trait and
//! the derive), never from this crate directly: the generated code names `::saltus_core`
//! (override with `#[describe(crate = path)]`).
//!
//! ```text
//! #[derive(Describe)]
//! #[describe(name = "dallavalle", source = "...", equation = "C_D = cd_inf + a / Re_p")]
//! struct Dallavalle {
//!     /// drag coefficient at infinite Re_p
//!     #[param(range = "[0, 10]", unit = "-")]
//!     cd_inf: f64,
//! }
//! ```
//!
//! Struct attributes (`#[describe(...)]`, `Describe` only):
//! * `name = "..."` (required): the registered model name.
//! * `source = ...`, `equation = ...` (required): a string literal, or an expression of
//!   type `&'static str` evaluated with `self` in scope (models whose text depends on an
//!   option, e.g. `source = self.form.source()`).
//! * `check = path` : a `fn(&Self) -> Result<(), ParamError>` run after the field
//!   relations below (constraints the attributes cannot say).
//! * `limits = [...]`: the model's declared limits (`saltus_core::Limit`), an expression
//!   evaluated with `self` in scope, checked by `saltus closure check`.
//! * `crate = path`: path of saltus-core (default `::saltus_core`).
//!
//! Field attributes (`#[param(...)]`):
//! * `range = "(0, 100]"`, interval notation with `inf` / `-inf`, and `unit = "-"`: required
//!   on `f64` and `Option<f64>` fields (an `Option` is listed only when set).
//! * `description = "..."`: the one-line meaning; the field's doc comment when absent
//!   (lines joined, markdown escapes `\[`, `\]` removed). One of the two is required.
//! * `value = expr`: list the field as a real parameter of this value (an `f64`
//!   expression with `self` in scope) whatever its type; needs `range` and `unit`.
//! * `less_than = other_field`, `greater_than = other_field`: a constraint between two
//!   real parameters, reported as `< other (value)` / `> other (value)`.
//! * `skip`: not listed.
//!
//! Any other field type is described by its `saltus_core::param::DescribeField` impl:
//! `bool` (an option `true`/`false`), `Option<T>`, and types deriving [`Params`] (a
//! sub-table struct whose keys are listed as `field.key`, an enum of unit variants listed
//! as a string option with its allowed values, or an internally tagged enum listed as the
//! option `field.type` followed by the parameters of the chosen variant). Serde's
//! `rename`, `rename_all` (snake_case, lowercase, kebab-case) and `tag` are followed so that
//! the listed keys and values are those of the TOML.

use proc_macro::TokenStream;
use proc_macro2::{Span, TokenStream as TokenStream2};
use quote::{quote, ToTokens};
use syn::{parse_macro_input, Data, DeriveInput, Expr, Fields, Ident, Lit, LitStr, Path, Type};

/// Implement `saltus_core::Describe` (name, source, equation, parameters, string options,
/// constraints, declared limits) from attributes; see the crate documentation.
#[proc_macro_derive(Describe, attributes(describe, param))]
pub fn derive_describe(input: TokenStream) -> TokenStream {
    let input = parse_macro_input!(input as DeriveInput);
    expand(&input, true).unwrap_or_else(syn::Error::into_compile_error).into()
}

/// Implement `saltus_core::param::DescribeField` for a sub-table struct, a string option
/// enum (unit variants) or an internally tagged enum of sub-tables; see the crate
/// documentation.
#[proc_macro_derive(Params, attributes(describe, param))]
pub fn derive_params(input: TokenStream) -> TokenStream {
    let input = parse_macro_input!(input as DeriveInput);
    expand(&input, false).unwrap_or_else(syn::Error::into_compile_error).into()
}

#[derive(Default)]
struct ModelAttrs {
    name: Option<LitStr>,
    source: Option<Expr>,
    equation: Option<Expr>,
    check: Option<Expr>,
    limits: Option<Expr>,
    krate: Option<Path>,
}

#[derive(Default)]
struct FieldAttrs {
    range: Option<LitStr>,
    unit: Option<LitStr>,
    description: Option<LitStr>,
    value: Option<Expr>,
    less_than: Option<Ident>,
    greater_than: Option<Ident>,
    skip: bool,
}

#[derive(Default)]
struct SerdeAttrs {
    rename: Option<String>,
    rename_all: Option<String>,
    tag: Option<String>,
}

fn model_attrs(input: &DeriveInput) -> syn::Result<ModelAttrs> {
    let mut a = ModelAttrs::default();
    for attr in input.attrs.iter().filter(|a| a.path().is_ident("describe")) {
        attr.parse_nested_meta(|meta| {
            if meta.path.is_ident("name") {
                a.name = Some(meta.value()?.parse()?);
            } else if meta.path.is_ident("source") {
                a.source = Some(meta.value()?.parse()?);
            } else if meta.path.is_ident("equation") {
                a.equation = Some(meta.value()?.parse()?);
            } else if meta.path.is_ident("check") {
                a.check = Some(meta.value()?.parse()?);
            } else if meta.path.is_ident("limits") {
                a.limits = Some(meta.value()?.parse()?);
            } else if meta.path.is_ident("crate") {
                a.krate = Some(meta.value()?.parse()?);
            } else {
                return Err(meta.error("expected one of name, source, equation, check, limits, crate"));
            }
            Ok(())
        })?;
    }
    Ok(a)
}

fn field_attrs(attrs: &[syn::Attribute]) -> syn::Result<FieldAttrs> {
    let mut a = FieldAttrs::default();
    for attr in attrs.iter().filter(|a| a.path().is_ident("param")) {
        attr.parse_nested_meta(|meta| {
            if meta.path.is_ident("range") {
                a.range = Some(meta.value()?.parse()?);
            } else if meta.path.is_ident("unit") {
                a.unit = Some(meta.value()?.parse()?);
            } else if meta.path.is_ident("description") {
                a.description = Some(meta.value()?.parse()?);
            } else if meta.path.is_ident("value") {
                a.value = Some(meta.value()?.parse()?);
            } else if meta.path.is_ident("less_than") {
                a.less_than = Some(meta.value()?.parse()?);
            } else if meta.path.is_ident("greater_than") {
                a.greater_than = Some(meta.value()?.parse()?);
            } else if meta.path.is_ident("skip") {
                a.skip = true;
            } else {
                return Err(
                    meta.error("expected one of range, unit, description, value, less_than, greater_than, skip")
                );
            }
            Ok(())
        })?;
    }
    Ok(a)
}

/// The serde attributes that decide TOML keys and values; others are ignored.
fn serde_attrs(attrs: &[syn::Attribute]) -> syn::Result<SerdeAttrs> {
    let mut a = SerdeAttrs::default();
    for attr in attrs.iter().filter(|a| a.path().is_ident("serde")) {
        attr.parse_nested_meta(|meta| {
            let key = if meta.path.is_ident("rename") {
                &mut a.rename
            } else if meta.path.is_ident("rename_all") {
                &mut a.rename_all
            } else if meta.path.is_ident("tag") {
                &mut a.tag
            } else {
                // skip the value of attributes such as `default = "path"` or
                // `skip_serializing_if = "..."`; flags such as `default` have none
                if meta.input.peek(syn::Token![=]) {
                    let _: Expr = meta.value()?.parse()?;
                } else if meta.input.peek(syn::token::Paren) {
                    let _content;
                    syn::parenthesized!(_content in meta.input);
                    let _: TokenStream2 = _content.parse()?;
                }
                return Ok(());
            };
            let s: LitStr = meta.value()?.parse()?;
            *key = Some(s.value());
            Ok(())
        })?;
    }
    Ok(a)
}

/// The doc comment as one line: lines trimmed and joined, markdown escapes of brackets
/// removed (rustdoc needs them, a terminal does not).
fn doc_comment(attrs: &[syn::Attribute]) -> Option<String> {
    let mut lines = Vec::new();
    for attr in attrs.iter().filter(|a| a.path().is_ident("doc")) {
        if let syn::Meta::NameValue(nv) = &attr.meta {
            if let Expr::Lit(syn::ExprLit { lit: Lit::Str(s), .. }) = &nv.value {
                let line = s.value().trim().to_string();
                if !line.is_empty() {
                    lines.push(line);
                }
            }
        }
    }
    (!lines.is_empty()).then(|| lines.join(" ").replace("\\[", "[").replace("\\]", "]"))
}

fn rename_variant(name: &str, rule: Option<&str>, span: Span) -> syn::Result<String> {
    let snake = || {
        let mut s = String::new();
        for (i, c) in name.chars().enumerate() {
            if c.is_uppercase() && i > 0 {
                s.push('_');
            }
            s.extend(c.to_lowercase());
        }
        s
    };
    Ok(match rule {
        None => name.to_string(),
        Some("snake_case") => snake(),
        Some("kebab-case") => snake().replace('_', "-"),
        Some("lowercase") => name.to_lowercase(),
        Some("UPPERCASE") => name.to_uppercase(),
        Some(other) => {
            return Err(syn::Error::new(
                span,
                format!("serde rename_all = \"{other}\" is not supported by this derive"),
            ))
        }
    })
}

/// `"(0, 100]"` -> a `ParamRange` expression, checked at compile time with the grammar
/// `ParamRange::from_str` reads at run time (`saltus-interval`).
fn range_tokens(lit: &LitStr, krate: &TokenStream2) -> syn::Result<TokenStream2> {
    let (lo, hi) = saltus_interval::parse(&lit.value()).map_err(|e| syn::Error::new(lit.span(), e))?;
    let bound = |e| match e {
        saltus_interval::End::Unbounded => quote!(#krate::param::Bound::Unbounded),
        saltus_interval::End::Open(x) => {
            let l = proc_macro2::Literal::f64_suffixed(x);
            quote!(#krate::param::Bound::Open(#l))
        }
        saltus_interval::End::Closed(x) => {
            let l = proc_macro2::Literal::f64_suffixed(x);
            quote!(#krate::param::Bound::Closed(#l))
        }
    };
    let (lo, hi) = (bound(lo), bound(hi));
    Ok(quote!(#krate::param::ParamRange { lo: #lo, hi: #hi }))
}

fn is_f64(ty: &Type) -> bool {
    matches!(ty, Type::Path(p) if p.qself.is_none() && p.path.is_ident("f64"))
}

/// `Option<f64>` (also spelled `std::option::Option<f64>`).
fn is_option_f64(ty: &Type) -> bool {
    let Type::Path(p) = ty else { return false };
    let Some(last) = p.path.segments.last() else { return false };
    if last.ident != "Option" {
        return false;
    }
    match &last.arguments {
        syn::PathArguments::AngleBracketed(args) => {
            args.args.len() == 1 && matches!(args.args.first(), Some(syn::GenericArgument::Type(t)) if is_f64(t))
        }
        _ => false,
    }
}

fn expand(input: &DeriveInput, model: bool) -> syn::Result<TokenStream2> {
    let attrs = model_attrs(input)?;
    let krate = attrs.krate.as_ref().map_or_else(|| quote!(::saltus_core), ToTokens::to_token_stream);
    let ty = &input.ident;
    let (impl_g, ty_g, where_g) = input.generics.split_for_impl();
    let serde = serde_attrs(&input.attrs)?;

    let (body, constraints) = match &input.data {
        Data::Struct(s) => struct_body(&s.fields, &krate)?,
        Data::Enum(e) if !model => (enum_body(e, &serde, &krate, input)?, Vec::new()),
        _ => {
            return Err(syn::Error::new_spanned(
                &input.ident,
                "#[derive(Describe)] takes a struct (derive Params on option enums and sub-tables)",
            ))
        }
    };

    let field_impl = quote! {
        impl #impl_g #krate::param::DescribeField for #ty #ty_g #where_g {
            #[allow(unused_variables)]
            fn describe_field(&self, prefix: &str, doc: &'static str, out: &mut #krate::param::ParamSet) {
                #body
            }
        }
    };
    if !model {
        return Ok(field_impl);
    }

    let need = |v: &Option<Expr>, what: &str| {
        v.clone()
            .ok_or_else(|| syn::Error::new_spanned(&input.ident, format!("#[describe({what} = \"...\")] is required")))
    };
    let name = attrs.name.clone().ok_or_else(|| {
        syn::Error::new_spanned(&input.ident, "#[describe(name = \"...\")] is required: the registered model name")
    })?;
    let source = need(&attrs.source, "source")?;
    let equation = need(&attrs.equation, "equation")?;
    let check = attrs.check.as_ref().map(|c| quote!((#c)(self)?;));
    let limits = attrs.limits.as_ref().map(|l| {
        quote! {
            fn limits(&self) -> ::std::vec::Vec<#krate::param::Limit> {
                ::std::vec::Vec::from(#l)
            }
        }
    });
    Ok(quote! {
        #field_impl
        impl #impl_g #krate::param::Describe for #ty #ty_g #where_g {
            fn name(&self) -> &'static str { #name }
            fn source(&self) -> &'static str { #source }
            fn equation(&self) -> &'static str { #equation }
            fn params(&self) -> ::std::vec::Vec<#krate::param::Param> {
                let mut set = #krate::param::ParamSet::default();
                #krate::param::DescribeField::describe_field(self, "", "", &mut set);
                set.params
            }
            fn choices(&self) -> ::std::vec::Vec<#krate::param::Choice> {
                let mut set = #krate::param::ParamSet::default();
                #krate::param::DescribeField::describe_field(self, "", "", &mut set);
                set.choices
            }
            fn check_constraints(&self) -> ::std::result::Result<(), #krate::param::ParamError> {
                #(#constraints)*
                #check
                Ok(())
            }
            #limits
        }
    })
}

fn struct_body(fields: &Fields, krate: &TokenStream2) -> syn::Result<(TokenStream2, Vec<TokenStream2>)> {
    let mut body = TokenStream2::new();
    let mut constraints = Vec::new();
    let named = match fields {
        Fields::Named(n) => n.named.iter().collect::<Vec<_>>(),
        Fields::Unit => Vec::new(),
        Fields::Unnamed(u) if u.unnamed.is_empty() => Vec::new(),
        Fields::Unnamed(u) => return Err(syn::Error::new_spanned(u, "fields must be named (they are TOML keys)")),
    };
    for f in named {
        let a = field_attrs(&f.attrs)?;
        if a.skip {
            continue;
        }
        let ident = f.ident.as_ref().ok_or_else(|| syn::Error::new_spanned(f, "unnamed field"))?;
        let key =
            serde_attrs(&f.attrs)?.rename.unwrap_or_else(|| ident.to_string().trim_start_matches("r#").to_string());
        let doc = match (&a.description, doc_comment(&f.attrs)) {
            (Some(d), _) => d.value(),
            (None, Some(d)) => d,
            (None, None) => {
                return Err(syn::Error::new_spanned(
                    ident,
                    "document this parameter: a doc comment or #[param(description = \"...\")]",
                ))
            }
        };
        let real = a.value.is_some() || is_f64(&f.ty) || is_option_f64(&f.ty);
        if real {
            let (Some(range), Some(unit)) = (&a.range, &a.unit) else {
                return Err(syn::Error::new_spanned(
                    ident,
                    "a real parameter needs #[param(range = \"(lo, hi]\", unit = \"...\")] (unit \"-\" when dimensionless)",
                ));
            };
            let range = range_tokens(range, krate)?;
            let push = |value: TokenStream2| {
                quote! {
                    out.params.push(#krate::param::Param::new(
                        #krate::param::join_key(prefix, #key), #value, #range, #unit, #doc,
                    ));
                }
            };
            body.extend(match (&a.value, is_option_f64(&f.ty)) {
                (Some(v), _) => push(quote!(#v)),
                (None, true) => {
                    let p = push(quote!(v));
                    quote!(if let ::std::option::Option::Some(v) = self.#ident { #p })
                }
                (None, false) => push(quote!(self.#ident)),
            });
        } else {
            if a.range.is_some() || a.unit.is_some() {
                return Err(syn::Error::new_spanned(
                    ident,
                    "range and unit apply to f64 fields (or with `value = expr`); this field is described by its type",
                ));
            }
            body.extend(quote! {
                #krate::param::DescribeField::describe_field(
                    &self.#ident, &#krate::param::join_key(prefix, #key), #doc, out,
                );
            });
        }
        for (other, op, word) in [(&a.less_than, quote!(<), "<"), (&a.greater_than, quote!(>), ">")] {
            if let Some(other) = other {
                let fmt = format!("{word} {other} ({{}})");
                constraints.push(quote! {
                    if !(self.#ident #op self.#other) {
                        return Err(#krate::param::ParamError::new(#key, self.#ident, format!(#fmt, self.#other)));
                    }
                });
            }
        }
    }
    Ok((body, constraints))
}

fn enum_body(
    e: &syn::DataEnum,
    serde: &SerdeAttrs,
    krate: &TokenStream2,
    input: &DeriveInput,
) -> syn::Result<TokenStream2> {
    let mut names = Vec::new();
    let mut arms = Vec::new();
    let mut inner = Vec::new();
    let unit_only = e.variants.iter().all(|v| matches!(v.fields, Fields::Unit));
    for v in &e.variants {
        let vs = serde_attrs(&v.attrs)?;
        let name = match vs.rename {
            Some(r) => r,
            None => rename_variant(&v.ident.to_string(), serde.rename_all.as_deref(), v.ident.span())?,
        };
        let id = &v.ident;
        match &v.fields {
            Fields::Unit => arms.push(quote!(Self::#id => #name)),
            Fields::Named(n) if n.named.is_empty() => arms.push(quote!(Self::#id {} => #name)),
            Fields::Unnamed(u) if u.unnamed.len() == 1 => {
                arms.push(quote!(Self::#id(_) => #name));
                inner.push(quote! {
                    Self::#id(inner) => #krate::param::DescribeField::describe_field(inner, prefix, doc, out),
                });
            }
            _ => {
                return Err(syn::Error::new_spanned(
                    v,
                    "variants are unit, empty `{}` or one sub-table struct (derive Params on that struct)",
                ))
            }
        }
        names.push(name);
    }
    if unit_only {
        return Ok(quote! {
            let value = match self { #(#arms,)* };
            out.choices.push(#krate::param::Choice {
                name: prefix.to_string(),
                value: value.to_string(),
                allowed: ::std::vec![#(#names),*],
                doc,
            });
        });
    }
    let Some(tag) = &serde.tag else {
        return Err(syn::Error::new_spanned(
            &input.ident,
            "an enum with sub-table variants must be internally tagged: #[serde(tag = \"type\")]",
        ));
    };
    Ok(quote! {
        let value = match self { #(#arms,)* };
        out.choices.push(#krate::param::Choice {
            name: #krate::param::join_key(prefix, #tag),
            value: value.to_string(),
            allowed: ::std::vec![#(#names),*],
            doc,
        });
        #[allow(unreachable_patterns)]
        match self {
            #(#inner)*
            _ => {}
        }
    })
}
