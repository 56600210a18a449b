// Vite handles CSS imports; tell TypeScript about them.
declare module "*.css";
